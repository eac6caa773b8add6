// SPDX-License-Identifier: MIT
// Unit: the "prescribed" backend (backends/prescribed): flow maps, RK4 order, walls, species,
// restart.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "fluid_test_scenes.hpp"
#include "sadr/common/status.hpp"
#include "sadr/fluid/builtin_backends.hpp"

namespace sadr::fluid {
namespace {

std::unique_ptr<FluidBackend> make() {
  BackendRegistry r;
  register_builtin_backends(r);
  return r.create("prescribed");
}

/// One fluid particle at x in a walled 2D box [-4, 4]^2.
struct One {
  FluidModel model;
  ParticleState state;
  explicit One(std::array<double, 3> x) {
    model.box.dimension = 2;
    model.box.lo = {-4, -4, 0};
    model.box.hi = {4, 4, 1};
    model.box.periodic = {false, false, false};
    model.smoothing_length = 0.5;
    state.dimension = 2;
    state.resize(1, true);
    state.positions = {x[0], x[1], x[2]};
    state.masses = {1.0};
    state.densities = {1.0};
  }
};

double distance_after_one_period(std::uint32_t steps, bool rk4) {
  One s({1.0, 0.0, 0.0});
  const double period = 1.0;
  s.model.backend_parameters = {
      {"field", 3}, {"omega", 2 * std::numbers::pi / period}, {"integrator", rk4 ? 1.0 : 0.0}};
  s.model.max_time_step = period / steps;
  auto b = make();
  b->initialize(s.model, s.state, {});
  for (std::uint32_t k = 0; k < steps; ++k) b->advance(k, period / steps);
  ParticleState out;
  b->read_state(out);
  return std::hypot(out.positions[0] - 1.0, out.positions[1]);
}

// Solid-body rotation: back at the start after one period; RK4 converges with order 4.
TEST(Prescribed, RotationReturnsAfterOnePeriodRk4OrderFour) {
  double prev = 0;
  for (const std::uint32_t n : {8u, 16u, 32u, 64u}) {
    const double e = distance_after_one_period(n, true);
    std::printf("RESULT prescribed rotation rk4 steps=%u error=%.3e", n, e);
    if (prev > 0) {
      const double order = std::log2(prev / e);
      std::printf(" observed_order=%.3f", order);
      EXPECT_GT(order, 3.8) << n;
      EXPECT_LT(order, 4.2) << n;
    }
    std::printf("\n");
    prev = e;
  }
  EXPECT_LT(distance_after_one_period(8, false), 1e-13);  // the exact map
}

// The exact maps of the other fields, and v = u(x) after the step.
TEST(Prescribed, ExactMapsOfUniformShearAndPoiseuille) {
  struct Case {
    std::map<std::string, double> p;
    std::array<double, 2> x_after, v_after;
  };
  const Case cases[] = {
      {{{"field", 0}, {"ux", 0.3}, {"uy", -0.2}}, {0.5 + 0.6, 0.25 - 0.4}, {0.3, -0.2}},
      {{{"field", 1}, {"shear_rate", 2.0}, {"y0", -0.25}}, {0.5 + 2 * 0.5 * 2, 0.25}, {1.0, 0}},
      {{{"field", 2}, {"max_velocity", 1.0}, {"wall_lo", -0.75}, {"wall_hi", 1.25}},
       {0.5 + 2 * 1.0, 0.25},
       {1.0, 0}},
  };
  for (const auto& c : cases) {
    One s({0.5, 0.25, 0.0});
    s.model.backend_parameters = c.p;
    auto b = make();
    b->initialize(s.model, s.state, {});
    b->advance(0, 2.0);
    ParticleState out;
    b->read_state(out);
    EXPECT_NEAR(out.positions[0], c.x_after[0], 1e-14);
    EXPECT_NEAR(out.positions[1], c.x_after[1], 1e-14);
    EXPECT_NEAR(out.velocities[0], c.v_after[0], 1e-14);
    EXPECT_NEAR(out.velocities[1], c.v_after[1], 1e-14);
  }
}

// Deterministic species on particles translated by a uniform flow in a periodic box: the
// relative positions never change, so the result is the static backend's (round-off).
TEST(Prescribed, SpeciesOnATranslatedLatticeEqualStatic) {
  test::LatticeSpec ls;
  ls.n = {12, 8, 1};
  ls.dx = 0.1;
  ls.periodic = {true, true, true};
  FluidModel m;
  ParticleState p = test::make_lattice(ls, m.box);
  m.smoothing_length = 0.3;
  m.species.push_back({"A", 0.02, true, {}, {}});
  std::vector<double> c0(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) c0[i] = std::sin(5.2 * p.positions[3 * i]);
  BackendRegistry r;
  register_builtin_backends(r);
  auto st = r.create("static");
  st->initialize(m, p, {c0});
  FluidModel mp = m;
  mp.backend_parameters = {{"field", 0}, {"ux", 0.37}};
  auto pr = make();
  pr->initialize(mp, p, {c0});
  for (std::uint64_t k = 0; k < 10; ++k) {
    st->advance(k, 0.05);
    pr->advance(k, 0.05);
  }
  const auto& a = st->concentrations(0);
  const auto& b = pr->concentrations(0);
  double err = 0, scale = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    err = std::max(err, std::fabs(a[i] - b[i]));
    scale = std::max(scale, std::fabs(a[i]));
  }
  EXPECT_LT(err, 1e-12 * scale) << err;
  // save/restore continues bit-identically
  auto again = make();
  again->initialize(mp, p, {c0});
  again->restore(pr->save());
  pr->advance(10, 0.05);
  again->advance(10, 0.05);
  EXPECT_EQ(pr->concentrations(0), again->concentrations(0));
  ParticleState o1, o2;
  pr->read_state(o1);
  again->read_state(o2);
  EXPECT_EQ(o1.positions, o2.positions);
}

// A Poiseuille channel between wall layers: fluid particles move with u(y), walls stay.
TEST(Prescribed, WallParticlesStayFluidFollowsTheProfile) {
  test::LatticeSpec ls;
  ls.n = {10, 8, 1};
  ls.dx = 0.1;
  ls.periodic = {true, false, true};
  ls.wall_layers = 3;
  FluidModel m;
  const ParticleState p = test::make_lattice(ls, m.box);
  m.smoothing_length = 0.3;
  m.backend_parameters = {{"field", 2}, {"max_velocity", 0.2}, {"wall_lo", 0}, {"wall_hi", 0.8}};
  auto b = make();
  b->initialize(m, p, {});
  b->advance(0, 0.1);
  ParticleState out;
  b->read_state(out);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double y = p.positions[3 * i + 1];
    const double u = p.kind(i) == ParticleKind::kWall ? 0.0 : 4 * 0.2 * y * (0.8 - y) / 0.64;
    double x = p.positions[3 * i] + 0.1 * u;
    if (x >= m.box.hi[0]) x -= m.box.hi[0] - m.box.lo[0];
    EXPECT_NEAR(out.positions[3 * i], x, 1e-14) << i;
    EXPECT_EQ(out.positions[3 * i + 1], y) << i;
    EXPECT_NEAR(out.velocities[3 * i], u, 1e-14) << i;
  }
}

TEST(Prescribed, RefusesUnknownParametersAndBadValues) {
  One s({0.5, 0.25, 0.0});
  auto b = make();
  s.model.backend_parameters = {{"field", 7}};
  EXPECT_THROW(b->initialize(s.model, s.state, {}), InvalidArgument);
  s.model.backend_parameters = {{"omga", 1}};
  EXPECT_THROW(b->initialize(s.model, s.state, {}), InvalidArgument);
}

}  // namespace
}  // namespace sadr::fluid
