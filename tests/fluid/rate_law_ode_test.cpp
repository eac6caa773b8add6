// SPDX-License-Identifier: MIT
// Rate laws in the deterministic path (static backend, no transport: every
// particle is a well-mixed reactor) against the exact solution of the ODE.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

#include "fluid_test_scenes.hpp"
#include "sadr/fluid/builtin_backends.hpp"
#include "static/static_backend.hpp"

namespace sadr::fluid {
namespace {

std::string sci(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

/// Root of g on (lo, hi) by bisection to machine precision (g monotone).
double solve(const std::function<double(double)>& g, double lo, double hi) {
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    if ((g(mid) > 0) == (g(lo) > 0)) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return 0.5 * (lo + hi);
}

/// S -> P with `law` on a 4 x 4 lattice; E (species 2) held by not reacting.
/// Returns C_S after time t (particle 0; all are equal without transport).
std::vector<double> run(const rate_law::Definition& law, double s0, double e0, double t) {
  test::LatticeSpec ls;
  ls.n = {4, 4, 1};
  FluidModel m;
  ParticleState p = test::make_lattice(ls, m.box);
  m.smoothing_length = 2.0;
  m.species.push_back({"S", 0.0, true, {}, {}});
  m.species.push_back({"P", 0.0, true, {}, {}});
  m.species.push_back({"E", 0.0, true, {}, {}});
  ReactionSpec rx;
  rx.def.name = "convert";
  rx.reactants = {{0, 1}};
  rx.products = {{1, 1}};
  rx.def.law = law;
  m.reactions.push_back(rx);
  m.max_time_step = 1e-3;
  m.force_time_step = true;
  StaticBackend b;
  b.initialize(m, p,
               {std::vector<double>(p.size(), s0), std::vector<double>(p.size(), 0.0),
                std::vector<double>(p.size(), e0)});
  b.advance(0, t);
  std::vector<double> out;
  for (int s = 0; s < 3; ++s) out.push_back(b.concentrations(s)[0]);
  for (std::size_t i = 1; i < p.size(); ++i) EXPECT_EQ(b.concentrations(0)[i], out[0]);
  return out;
}

rate_law::Definition michaelis() {
  rate_law::Definition d;
  d.type = rate_law::Type::kMichaelisMenten;
  d.kcat = 0.8;
  d.km = 0.5;
  d.substrate = std::string("S");
  d.catalyst = std::string("E");
  return d;
}

// dS/dt = -kcat E S/(Km + S): Km ln(S0/S) + S0 - S = kcat E t. Heun with dt = 1e-3.
// A law of the time t (docs/method.md section 4c): dC/dt = -k exp(-a t) C, exact
// C0 exp(-k (1 - exp(-a t)) / a), on every backend whose integrator evaluates laws at
// the time of each stage (static: Heun; sdpd: predictor-corrector; particles at rest
// on a lattice, k_B T = 0, no diffusion). Second order in the sub-step: 1e-3 -> <1e-7.
TEST(RateLawOde, ALawOfTimeMatchesItsExactSolutionOnStaticAndSdpd) {
  const double k = 1.5, a = 2.0, c0 = 3.0, t = 1.0;
  rate_law::Definition law;
  law.type = rate_law::Type::kExpression;
  law.expression = "k*exp(-a*t)*C";
  law.parameters = {{"k", k}, {"a", a}};
  BackendRegistry registry;
  register_builtin_backends(registry);
  for (const std::string name : {"static", "sdpd"}) {
    test::LatticeSpec ls;
    ls.n = {12, 12, 1};  // sdpd: a periodic axis longer than twice its cutoff
    FluidModel m;
    ParticleState p = test::make_lattice(ls, m.box);
    m.smoothing_length = 2.0;
    m.species.push_back({"C", 0.0, true, {}, {}});
    ReactionSpec rx;
    rx.def.name = "decay";
    rx.reactants = {{0, 1}};
    rx.def.law = law;
    m.reactions.push_back(rx);
    m.max_time_step = 1e-3;
    m.force_time_step = true;
    auto b = registry.create(name);
    b->initialize(m, p, {std::vector<double>(p.size(), c0)});
    b->advance(0, 0.5);
    b->advance(1, 0.5);  // two calls: the law's t carries over between advances
    const double exact = c0 * std::exp(-k * (1 - std::exp(-a * t)) / a);
    const double err = std::fabs(b->concentrations(0)[0] - exact);
    std::printf("%s: C(1) = %.12f, exact %.12f, error %s\n", name.c_str(), b->concentrations(0)[0],
                exact, sci(err).c_str());
    EXPECT_LT(err, 1e-7 * c0) << name;
  }
}

TEST(RateLawOde, MichaelisMentenMatchesExactSolution) {
  const double s0 = 2, e0 = 1.5, t = 1.5;
  const auto c = run(michaelis(), s0, e0, t);
  const double exact =
      solve([&](double s) { return 0.5 * std::log(s0 / s) + s0 - s - 0.8 * e0 * t; }, 1e-9, s0);
  EXPECT_NEAR(c[0], exact, 1e-7 * s0);
  EXPECT_NEAR(c[0] + c[1], s0, 1e-13);  // S + P conserved
  EXPECT_EQ(c[2], e0);                  // the catalyst is not consumed
  RecordProperty("abs_error", sci(std::fabs(c[0] - exact)));
}

// dA/dt = -Vmax A^2/(K^2 + A^2): K^2 (1/A - 1/A0) - (A - A0) = Vmax t (n = 2).
TEST(RateLawOde, HillMatchesExactSolution) {
  rate_law::Definition d;
  d.type = rate_law::Type::kHill;
  d.vmax = 1.2;
  d.half = 0.7;
  d.n = 2;
  d.of = std::string("S");
  const double a0 = 3, t = 2;
  const auto c = run(d, a0, 0.0, t);
  const double exact =
      solve([&](double a) { return 0.49 * (1 / a - 1 / a0) - (a - a0) - 1.2 * t; }, 1e-6, a0);
  EXPECT_NEAR(c[0], exact, 1e-7 * a0);
  RecordProperty("abs_error", sci(std::fabs(c[0] - exact)));
}

// An expression spelling the built-in law gives identical concentrations.
TEST(RateLawOde, ExpressionSpellingMichaelisMentenIsIdentical) {
  rate_law::Definition e;
  e.type = rate_law::Type::kExpression;
  e.expression = std::string("kcat*E*S/(Km+S)");
  e.parameters = {{"kcat", 0.8}, {"Km", 0.5}};
  EXPECT_EQ(run(e, 2, 1.5, 0.5), run(michaelis(), 2, 1.5, 0.5));
}

}  // namespace
}  // namespace sadr::fluid
