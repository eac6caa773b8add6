// SPDX-License-Identifier: MIT
// Property: the force of the fluid on a body (FluidModel::body_forces, sdpd_body_forces.cpp).
// A fluid driven by the body acceleration g through a periodic box past a solid disk (2D) or
// sphere (3D) of wall particles:
//  - every step, exactly: (change of the fluid's momentum) / tau = M g - F, M the fluid's mass
//    and F the reported force (the mean over the step of what the integrator applied);
//  - at steady state nothing else holds the fluid: F = M g (within 1 %, the residual
//    acceleration of the fluid);
//  - the torque of a symmetric body about its centroid is zero;
//  - with the stationary, Adami and Morris walls; refused without wall particles or by a backend
//    that does not compute it.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "disk_in_box_scene.hpp"
#include "sadr/common/status.hpp"
#include "sadr/fluid/builtin_backends.hpp"
#include "sdpd/sdpd_backend.hpp"

namespace sadr::fluid {
namespace {

constexpr double kG = 1.0, kEta = 1.0, kR = 0.2;

using Scene = test::DiskInBox;
Scene disk_in_box(int dim, int n, WallModel wm) {
  return test::disk_in_box(dim, n, wm, kR, kEta, kG);
}

struct Momentum {
  std::array<double, 3> p{};
  double mass = 0;
};

Momentum fluid_momentum(SdpdBackend& b) {
  ParticleState st;
  b.read_state(st);
  Momentum m;
  for (std::size_t i = 0; i < st.size(); ++i) {
    if (st.kind(i) != ParticleKind::kFluid) continue;
    m.mass += st.masses[i];
    for (int a = 0; a < 3; ++a) m.p[a] += st.masses[i] * st.velocities[3 * i + a];
  }
  return m;
}

// Runs `steps` coupling steps of length tau; checks the momentum identity at every step and
// returns the last step's report.
StepReport run_checking_balance(SdpdBackend& b, int dim, int steps, double tau) {
  StepReport rep;
  Momentum before = fluid_momentum(b);
  for (int k = 0; k < steps; ++k) {
    rep = b.advance(static_cast<std::uint64_t>(k), tau);
    const Momentum after = fluid_momentum(b);
    EXPECT_EQ(rep.body_forces.size(), 1U);
    if (rep.body_forces.size() != 1) return rep;
    const BodyForce& f = rep.body_forces[0];
    EXPECT_EQ(f.name, "disk");
    const double mg = after.mass * kG;
    for (int a = 0; a < dim; ++a) {
      const double dpdt = (after.p[a] - before.p[a]) / tau;
      const double expect = (a == 0 ? mg : 0.0) - f.force[a];
      EXPECT_NEAR(dpdt, expect, 1e-9 * mg) << "step " << k << " axis " << a;
    }
    before = after;
  }
  return rep;
}

void expect_steady_balance(int dim, int n, WallModel wm, int steps, double tau) {
  Scene s = disk_in_box(dim, n, wm);
  SdpdBackend b;
  b.initialize(s.model, s.state, {});
  const StepReport rep = run_checking_balance(b, dim, steps, tau);
  ASSERT_EQ(rep.body_forces.size(), 1U);
  const BodyForce& f = rep.body_forces[0];
  const double mg = fluid_momentum(b).mass * kG;
  EXPECT_NEAR(f.force[0] / mg, 1.0, 0.01);  // steady: the body holds the fluid
  for (int a = 1; a < 3; ++a) EXPECT_NEAR(f.force[a] / mg, 0.0, 1e-3) << a;
  // symmetric body, flow along x: no torque about its centre (2D: z only)
  const double lever = mg * kR;
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(f.torque[a] / lever, 0.0, 1e-3) << a;
  for (int a = 0; a < dim; ++a) EXPECT_NEAR(f.reference[a], 0.5, 1e-12) << a;
}

// Viscous time (1/(kEta 4 pi^2)) ~ 0.025; the 2D flows settle by t = 0.5 (0.1 % of F), the
// sparser 3D array by t = 1 (at t = 0.5 its F is still 9 % short of M g).
TEST(SdpdForcesOnBodies, DiskStationaryWallsBalanceTheDrivingForce) {
  expect_steady_balance(2, 20, WallModel::kStationary, 10, 0.05);
}

TEST(SdpdForcesOnBodies, DiskAdamiWallsBalanceTheDrivingForce) {
  expect_steady_balance(2, 20, WallModel::kAdami, 10, 0.05);
}

TEST(SdpdForcesOnBodies, DiskMorrisWallsBalanceTheDrivingForce) {
  expect_steady_balance(2, 20, WallModel::kMorrisExtrapolated, 10, 0.05);
}

TEST(SdpdForcesOnBodies, SphereAdamiWallsBalanceTheDrivingForce) {
  expect_steady_balance(3, 10, WallModel::kAdami, 20, 0.05);
}

TEST(SdpdForcesOnBodies, NoWallParticleIsRefused) {
  Scene s = disk_in_box(2, 20, WallModel::kStationary);
  s.model.body_forces[0].particles = {0};  // a fluid particle (the box's corner)
  ASSERT_EQ(s.state.kind(0), ParticleKind::kFluid);
  SdpdBackend b;
  try {
    b.initialize(s.model, s.state, {});
    FAIL() << "accepted a body without wall particles";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("holds no wall particle"), std::string::npos) << e.what();
  }
}

TEST(SdpdForcesOnBodies, NoBodyForcesNoReport) {
  Scene s = disk_in_box(2, 20, WallModel::kStationary);
  s.model.body_forces.clear();
  SdpdBackend b;
  b.initialize(s.model, s.state, {});
  EXPECT_TRUE(b.advance(0, 0.01).body_forces.empty());
}

TEST(SdpdForcesOnBodies, ABackendWithoutThemRefuses) {
  Scene s = disk_in_box(2, 20, WallModel::kStationary);
  BackendRegistry registry;
  register_builtin_backends(registry);
  auto b = registry.create("static");
  try {
    b->initialize(s.model, s.state, {});
    FAIL() << "the static backend accepted body_forces";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("body_forces"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sadr::fluid
