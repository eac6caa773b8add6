// SPDX-License-Identifier: MIT
// The adaptive SSA (Model::method = kAdaptive; docs/method.md "Adaptive SSA"):
//  - with no abundant pair it fires exactly the exact NSM's events (walls, reservoirs,
//    Neumann sources, region reactions, a hybrid rate law, graph rebuilds);
//  - a snapshot mid-run resumes bit-identically (version 3 blob), and is refused by an
//    exact solver;
//  - counts never go negative, at extreme tolerances, with free walls and fast consumption;
//  - short error test: on the high-copy step (case c, adaptive_cases.hpp) the bias of mean
//    and variance stays below the tolerance (|b| <= eps + z* SE, family-wise 1e-4) at
//    eps = 0.1 and 0.01, and the validation sweep (adaptive_validation_test.cpp) does the
//    four decades.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "adaptive_cases.hpp"
#include "sadr/common/status.hpp"
#include "sadr/ssa/nsm_solver.hpp"
#include "ssa_test_support.hpp"

namespace sadr::ssa {
namespace {

/// 2D, 8 x 8 jittered particles with a wall column at x < 1: A (reservoir on the walls),
/// B (Neumann source, free walls if `free_b`), C immobile; A + B -> C, C -> A + B, a region
/// dimerisation, and 0 -> B at k F exp(-t) with F frozen (a hybrid law of t).
Model rich_model(SsaMethod method, double eps, double reservoir, bool free_b = false) {
  Model m = testing::diffusion_model(testing::make_box(2, 8.0, false), 2.0, 0.5);
  m.species = {{"A", 0.5}, {"B", 0.3}, {"C", 0.0}};
  m.reactions = {{"bind", {{0, 1}, {1, 1}}, {{2, 1}}, 0.3, {}, {}},
                 {"unbind", {{2, 1}}, {{0, 1}, {1, 1}}, 0.2, {}, {}},
                 {"dimer", {{0, 2}}, {{2, 1}}, 0.05, {}, {10, 11, 12, 20, 21}}};
  Reaction feed;
  feed.def.name = "feed";
  feed.products = {{1, 1}};
  rate_law::Definition d;
  d.type = rate_law::Type::kExpression;
  d.expression = "k*F*exp(-t)";
  d.parameters = {{"k", 2.0}};
  feed.def.law = d;
  m.reactions.push_back(feed);
  m.frozen_species = {"F"};
  m.reservoirs = {{0, reservoir, {}}};
  m.neumann = {{1, 2.0}};
  if (free_b) m.free_walls = {{1, {}}};
  m.method = method;
  m.tolerance = eps;
  return m;
}

ParticleState particles(std::uint64_t seed) {
  ParticleState p = testing::make_lattice(2, 8, 1.0, 0.3, 0.2, seed);
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.positions[3 * i] < 1.0) p.kinds[i] = ParticleKind::kWall;
  }
  return p;
}

std::vector<double> frozen(double scale) {
  std::vector<double> f(64);
  for (std::size_t i = 0; i < f.size(); ++i) f[i] = scale * static_cast<double>(i % 5);
  return f;
}

std::vector<std::int64_t> all_counts(const NsmSolver& s) {
  std::vector<std::int64_t> out;
  for (int sp = 0; sp < 3; ++sp) out.insert(out.end(), s.counts(sp).begin(), s.counts(sp).end());
  return out;
}

/// Stages of a coupled run: inputs, advance, particles move, inputs, advance.
void stages(NsmSolver& s, double t0, int n) {
  for (int k = 0; k < n; ++k) {
    s.set_inputs(s.time(), frozen(1.0 + 0.1 * k));
    s.advance(t0 + 0.4 * (k + 1));
    if (k % 2 == 1) s.update_graph(particles(3 + static_cast<std::uint64_t>(k)));
  }
}

NsmSolver start(const Model& m, std::uint64_t seed, std::int64_t a, std::int64_t b) {
  NsmSolver s(m, seed);
  s.update_graph(particles(1));
  s.set_counts(0, std::vector<std::int64_t>(64, a));
  s.set_counts(1, std::vector<std::int64_t>(64, b));
  return s;
}

// Low copy numbers (all < n_c = 100 at eps = 0.01, reservoirs hold round(20 V) < 100): no
// pair is ever abundant, and the adaptive solver fires the exact NSM's events, one for one.
TEST(Adaptive, WithoutAbundantPairsFiresTheExactEvents) {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    NsmSolver exact = start(rich_model(SsaMethod::kExact, 0.01, 20.0), seed, 10, 5);
    NsmSolver adapt = start(rich_model(SsaMethod::kAdaptive, 0.01, 20.0), seed, 10, 5);
    stages(exact, 0.0, 6);
    stages(adapt, 0.0, 6);
    ASSERT_GT(exact.events(), 1000u);
    EXPECT_EQ(adapt.leaped_molecules(), 0u);
    EXPECT_EQ(adapt.events(), exact.events());
    EXPECT_EQ(all_counts(adapt), all_counts(exact));
    EXPECT_EQ(adapt.time(), exact.time());
  }
}

// High copy numbers (n_c = 20 at eps = 0.05, thousands per voxel): leaps happen; a snapshot taken
// after some stages resumes bit-identically through graph rebuilds and new inputs, into a fresh
// solver of another seed and into the used one; the later snapshots are byte-identical.
TEST(Adaptive, RestoreContinuesBitIdentically) {
  const Model m = rich_model(SsaMethod::kAdaptive, 0.05, 5000.0);
  NsmSolver a = start(m, 7, 5000, 2000);
  stages(a, 0.0, 3);
  ASSERT_GT(a.leaped_molecules(), 0u);
  const std::string blob = a.save();
  const std::uint64_t leaped_at_snap = a.leaped_molecules();
  stages(a, a.time(), 4);
  const std::vector<std::int64_t> ref = all_counts(a);
  EXPECT_GT(a.leaped_molecules(), leaped_at_snap);

  NsmSolver b(m, 999);
  b.restore(blob);
  EXPECT_EQ(b.leaped_molecules(), leaped_at_snap);
  stages(b, b.time(), 4);
  EXPECT_EQ(all_counts(b), ref);
  EXPECT_EQ(b.events(), a.events());
  EXPECT_EQ(b.leaped_molecules(), a.leaped_molecules());
  EXPECT_EQ(b.save(), a.save());

  a.restore(blob);
  stages(a, a.time(), 4);
  EXPECT_EQ(all_counts(a), ref);

  // Not into an exact solver, nor an exact blob into an adaptive one.
  NsmSolver exact(rich_model(SsaMethod::kExact, 0.05, 5000.0), 7);
  EXPECT_THROW(exact.restore(blob), InvalidArgument);
  EXPECT_THROW(b.restore(exact.save()), InvalidArgument);
  // Another tolerance is another model.
  NsmSolver other(rich_model(SsaMethod::kAdaptive, 0.06, 5000.0), 7);
  EXPECT_THROW(other.restore(blob), InvalidArgument);
}

// Never a negative count: extreme tolerances (every window leaps up to ~all molecules at
// eps = 0.999; n_c = 10), free walls for B, and fast consumption by A + B -> C.
TEST(Adaptive, NeverANegativeCount) {
  for (double eps : {0.999, 0.5, 0.1, 1e-6}) {
    for (bool free_b : {false, true}) {
      Model m = rich_model(SsaMethod::kAdaptive, eps, 2000.0, free_b);
      m.reactions[0].def.rate = 30.0;  // bind: fast
      NsmSolver s = start(m, 11, 3000, 40);
      for (int k = 0; k < 8; ++k) {
        stages(s, s.time(), 1);
        for (const std::int64_t x : all_counts(s)) ASSERT_GE(x, 0) << "eps=" << eps;
      }
      if (eps >= 0.1) {
        EXPECT_GT(s.leaped_molecules(), 0u) << "eps=" << eps;
      }
    }
  }
}

// Case (c), short: the step of 1e4 molecules per voxel, R = 300, eps = 0.1 and 0.01;
// |b| <= eps + z* SE over all comparison points of both (family-wise 1e-4).
TEST(Adaptive, StepBiasStaysBelowTolerance) {
  const testing::LinearCase c = testing::lattice_step(10000);
  std::vector<testing::CaseResult> res;
  int points = 0;
  for (double eps : {0.1, 0.01}) {
    res.push_back(testing::run_linear_case(c, SsaMethod::kAdaptive, eps, 300, 5));
    points += 2 * res.back().points;
    RecordProperty("eps_" + std::to_string(res.size()), testing::describe(res.back()));
  }
  const double zs = testing::z_star(1e-4, points);
  for (const auto& r : res) {
    EXPECT_GT(r.points, 10);
    EXPECT_GT(r.leaped, 0u);
    EXPECT_LE(r.max_excess, zs) << testing::describe(r);
  }
}

// Reservoir leaps (Poisson emission) through Morris-scaled wall edges: the chain of
// MorrisReservoirs.ChainMeansMatchTheScaledGraphAndReachTheWallValueAtTheSurface with the left
// wall holding W = 20000 (every pair abundant at eps = 0.05, n_c = 20); the exact steady means
// are linear, m(x) = W (x_R - x) / (x_R - x_L) (that test checks the graph equations give it).
// R = 60 runs sampled once at T = 120 (the transient is below 5 molecules); per fluid voxel
// |b| <= eps + z* SE with SE = sqrt(m / R) / m (independent Poisson counts), 10 points,
// family-wise 1e-4.
TEST(Adaptive, MorrisReservoirChainReachesTheExactSteadyMeans) {
  const double h = 1.5, w_left = 20000.0, eps = 0.05;
  const double kappa = 1.0 / (2.0 * lucy_f(1.0, h, 1) / (1.0 + 0.01 * h * h));
  const double x_l = 0.5 + 1.0 / 3.0, x_r = 11.3;
  ParticleState p = testing::make_lattice(1, 12, 1.0);
  p.kinds[0] = p.kinds[11] = ParticleKind::kWall;
  Model m = testing::diffusion_model(testing::make_box(1, 12.0, false), h, kappa);
  m.reservoirs = {{0, w_left, {0}}, {0, 0.0, {11}}};
  m.morris_walls = {{{0}, {{x_l, 0, 0}, {1, 0, 0}, 0.0}}, {{11}, {{x_r, 0, 0}, {-1, 0, 0}, 0.0}}};
  m.method = SsaMethod::kAdaptive;
  m.tolerance = eps;
  const int runs = 60;
  std::vector<testing::Moments> mom(12);
  std::uint64_t leaped = 0;
  for (int r = 0; r < runs; ++r) {
    NsmSolver s(m, rng::mix_seed(4242, static_cast<std::uint64_t>(r)));
    s.update_graph(p);
    s.advance(120.0);
    for (int i = 1; i <= 10; ++i) mom[i].add(static_cast<double>(s.counts(0)[i]));
    leaped += s.leaped_molecules();
  }
  EXPECT_GT(leaped, 0u);
  const double zs = testing::z_star(1e-4, 10);
  double worst = 0;
  for (int i = 1; i <= 10; ++i) {
    const double x = p.positions[3 * i];
    const double exact = w_left * (x_r - x) / (x_r - x_l);
    const double b = (mom[i].mean() - exact) / exact, se = std::sqrt(exact / runs) / exact;
    EXPECT_LE(std::abs(b), eps + zs * se)
        << "voxel " << i << " mean " << mom[i].mean() << " exact " << exact;
    worst = std::max(worst, std::abs(b));
  }
  RecordProperty("max_abs_relative_bias", std::to_string(worst));
}

// Reactions are never leaped: in one voxel (no edges, nothing diffuses) a high-copy
// Michaelis-Menten network E + S <-> ES -> E + P runs the exact NSM's events one for one.
TEST(Adaptive, WellMixedReactionsStayExact) {
  auto model = [](SsaMethod method) {
    Model m;
    m.species = {{"E", 0.1}, {"S", 0.1}, {"ES", 0.1}, {"P", 0.1}};
    m.reactions = {{"bind", {{0, 1}, {1, 1}}, {{2, 1}}, 0.01, {}, {}},
                   {"unbind", {{2, 1}}, {{0, 1}, {1, 1}}, 1.0, {}, {}},
                   {"cat", {{2, 1}}, {{0, 1}, {3, 1}}, 0.5, {}, {}}};
    m.box = testing::make_box(1, 1.0, false);
    m.smoothing_length = 0.4;
    m.method = method;
    m.tolerance = 0.001;
    return m;
  };
  const ParticleState p = testing::make_lattice(1, 1, 1.0);
  NsmSolver exact(model(SsaMethod::kExact), 9), adapt(model(SsaMethod::kAdaptive), 9);
  for (NsmSolver* s : {&exact, &adapt}) {
    s->update_graph(p);
    s->set_counts(0, std::vector<std::int64_t>{2000});
    s->set_counts(1, std::vector<std::int64_t>{50000});
    s->advance(1.0);
  }
  ASSERT_GT(exact.events(), 5000u);
  EXPECT_EQ(adapt.leaped_molecules(), 0u);
  EXPECT_EQ(adapt.events(), exact.events());
  for (int sp = 0; sp < 4; ++sp) EXPECT_EQ(adapt.counts(sp)[0], exact.counts(sp)[0]);
}

// A pair that becomes abundant during one long advance() is leaped from the next
// classification on (windows without abundant pairs end after an event budget).
TEST(Adaptive, SwitchesToLeapingWithinOneAdvance) {
  Model m = testing::diffusion_model(testing::make_box(1, 10.0, true), 1.5, 1.0);
  m.reactions = {{"birth", {}, {{0, 1}}, 5000.0, {}, {0}}};  // 0 -> A in voxel 0 only
  m.method = SsaMethod::kAdaptive;
  m.tolerance = 0.01;  // n_c = 100
  NsmSolver s(m, 3);
  s.update_graph(testing::make_lattice(1, 10, 1.0));
  s.advance(2.0);
  EXPECT_GT(s.leaped_molecules(), 0u);
  EXPECT_GT(s.leap_windows(), 0u);
  std::int64_t total = 0;
  for (const std::int64_t x : s.counts(0)) total += x;
  EXPECT_GT(total, 5000);  // about 10000 births (V = 1)
}

// The tolerance is checked where the model is (0 < eps < 1, adaptive only).
TEST(Adaptive, ToleranceOutOfRangeIsRefused) {
  Model m = testing::diffusion_model(testing::make_box(1, 4.0, false), 1.5, 1.0);
  m.method = SsaMethod::kAdaptive;
  for (double eps : {0.0, 1.0, -0.5, std::nan("")}) {
    m.tolerance = eps;
    const std::string msg = testing::message_of([&] { m.validate(); });
    EXPECT_NE(msg.find("tolerance"), std::string::npos) << eps << ": " << msg;
    EXPECT_NE(msg.find("0 < tolerance < 1"), std::string::npos) << msg;
  }
  m.method = SsaMethod::kExact;  // not read by the exact method
  EXPECT_NO_THROW(m.validate());
}

}  // namespace
}  // namespace sadr::ssa
