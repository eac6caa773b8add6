// SPDX-License-Identifier: MIT
// Property: bodies whose wall particles move (FluidModel::moving_bodies, sdpd_moving_bodies.cpp,
// docs/fluid-core.md "Moving walls"). A disk (2D) or sphere (3D) of wall particles in a periodic
// box of fluid driven by g, translating and turning:
//  - after every sub-step the wall particles sit at the closed-form rigid motion
//    c0 + V t + R(omega t)(x0 - c0) (wrapped into the periodic box) and carry the rigid-body
//    velocity V + omega axis x (x - c(t)) at their current position, evaluated here independently
//    of common/rigid_motion.hpp, to 1e-12;
//  - a restore continues bit-identically (positions, velocities, densities);
//  - other backends refuse a moving body, and so does the model with Morris walls on a region's
//    surface or on tangent planes of a turning body (a translating one is allowed);
//  - a body that leaves the box on a walled axis stops the run, naming the body and the time.
// The Galilean-invariance check of the drag is in sdpd_moving_bodies_flow_test.cpp.
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

constexpr double kR = 0.2;

/// The disk of disk_in_box made a moving body with velocity v, angular velocity w about `axis`
/// through the box centre.
test::DiskInBox moving_disk(int dim, int n, WallModel wm, std::array<double, 3> v, double w,
                            std::array<double, 3> axis = {0, 0, 1}) {
  test::DiskInBox s = test::disk_in_box(dim, n, wm, kR, 1.0, 1.0, 20.0);
  MovingBody body;
  body.name = "disk";
  body.particles = s.model.body_forces.front().particles;
  body.motion.velocity = v;
  body.motion.angular_velocity = w;
  body.motion.center = {0.5, 0.5, dim == 3 ? 0.5 : 0.0};
  body.motion.axis = axis;
  s.model.moving_bodies.push_back(body);
  return s;
}

/// The tangent planes of the disk's wall particles (as a scene's geometry gives them).
void add_tangents(test::DiskInBox& s) {
  const int dim = s.model.box.dimension;
  for (const std::uint32_t i : s.model.moving_bodies.front().particles) {
    std::array<double, 3> r{};
    double len = 0;
    for (int a = 0; a < dim; ++a) {
      r[a] = s.state.positions[3 * i + a] - 0.5;
      len += r[a] * r[a];
    }
    len = std::sqrt(len);
    if (!(len > 0)) continue;
    s.model.wall_tangents.particles.push_back(i);
    s.model.wall_tangents.depths.push_back(kR - len);
    for (int a = 0; a < 3; ++a) s.model.wall_tangents.normals.push_back(r[a] / len);
  }
}

/// Rodrigues' rotation of r by angle th about the unit axis k (written out here, not the
/// library's).
std::array<double, 3> turn(const std::array<double, 3>& r, const std::array<double, 3>& k,
                           double th) {
  const double c = std::cos(th), s = std::sin(th), kr = k[0] * r[0] + k[1] * r[1] + k[2] * r[2];
  return {r[0] * c + (k[1] * r[2] - k[2] * r[1]) * s + k[0] * kr * (1 - c),
          r[1] * c + (k[2] * r[0] - k[0] * r[2]) * s + k[1] * kr * (1 - c),
          r[2] * c + (k[0] * r[1] - k[1] * r[0]) * s + k[2] * kr * (1 - c)};
}

/// The largest deviation of the body's wall particles from the closed form at time t (positions
/// by the minimum image in the unit box, velocities from the current positions).
double deviation(const test::DiskInBox& s, const ParticleState& now, double t) {
  const int dim = s.model.box.dimension;
  const MovingBody& b = s.model.moving_bodies.front();
  const RigidMotion& m = b.motion;
  double worst = 0;
  std::array<double, 3> c{};
  for (int a = 0; a < 3; ++a) c[a] = m.center[a] + m.velocity[a] * t;
  for (const std::uint32_t i : b.particles) {
    std::array<double, 3> r0{};
    for (int a = 0; a < 3; ++a) r0[a] = s.state.positions[3 * i + a] - m.center[a];
    const std::array<double, 3> q = turn(r0, m.axis, m.angular_velocity * t);
    std::array<double, 3> arm{};
    for (int a = 0; a < dim; ++a) {
      double d = now.positions[3 * i + a] - (c[a] + q[a]);
      d -= std::round(d);  // unit periodic box
      worst = std::max(worst, std::fabs(d));
      arm[a] = q[a] + d;  // x - c(t) from the particle's own position
    }
    const auto& k = m.axis;
    const double w = m.angular_velocity;
    const std::array<double, 3> v{m.velocity[0] + w * (k[1] * arm[2] - k[2] * arm[1]),
                                  m.velocity[1] + w * (k[2] * arm[0] - k[0] * arm[2]),
                                  m.velocity[2] + w * (k[0] * arm[1] - k[1] * arm[0])};
    for (int a = 0; a < dim; ++a) {
      worst = std::max(worst, std::fabs(now.velocities[3 * i + a] - v[a]));
    }
  }
  return worst;
}

void check_follows(test::DiskInBox s, const char* what) {
  constexpr double kSub = 5e-4;  // below every stability limit: one sub-step per advance
  s.model.max_time_step = kSub;
  SdpdBackend b;
  b.initialize(s.model, s.state, {});
  ParticleState now;
  b.read_state(now);
  EXPECT_EQ(deviation(s, now, 0.0), 0.0) << what << ": t = 0";
  double worst = 0;
  std::uint64_t step = 0;
  for (; step < 40; ++step) {
    const StepReport rep = b.advance(step, kSub);
    ASSERT_EQ(rep.substeps, 1u) << what;
    b.read_state(now);
    worst = std::max(worst, deviation(s, now, rep.time));
  }
  const StepReport rep = b.advance(step, 0.2);  // many sub-steps: the body crosses the box
  EXPECT_GT(rep.substeps, 10u) << what;
  b.read_state(now);
  worst = std::max(worst, deviation(s, now, rep.time));
  std::printf("RESULT moving_body %s max deviation from the closed form %.3g\n", what, worst);
  EXPECT_LT(worst, 1e-12) << what;
}

TEST(MovingBodies, WallParticlesFollowTheClosedFormAtEverySubstep) {
  check_follows(moving_disk(2, 20, WallModel::kStationary, {-2.0, 1.0, 0.0}, 3.0), "2D stationary");
  test::DiskInBox adami = moving_disk(2, 20, WallModel::kAdami, {-2.0, 1.0, 0.0}, 3.0);
  add_tangents(adami);
  check_follows(adami, "2D adami");
  test::DiskInBox morris =
      moving_disk(2, 20, WallModel::kMorrisExtrapolated, {-2.0, 1.0, 0.0}, 0.0);
  morris.model.wall_regions.clear();
  add_tangents(morris);
  check_follows(morris, "2D morris (translating)");
  const double k = 1.0 / std::sqrt(3.0);
  check_follows(moving_disk(3, 8, WallModel::kAdami, {1.0, -0.5, 0.25}, 2.0, {k, k, k}),
                "3D adami");
}

TEST(MovingBodies, RestoreContinuesBitIdentically) {
  for (const WallModel wm : {WallModel::kStationary, WallModel::kAdami}) {
    test::DiskInBox s = moving_disk(2, 20, wm, {-2.0, 1.0, 0.0}, 3.0);
    if (wm == WallModel::kAdami) add_tangents(s);
    SdpdBackend a;
    a.initialize(s.model, s.state, {});
    a.advance(0, 0.03);
    const std::string blob = a.save();
    a.advance(1, 0.03);
    ParticleState sa;
    a.read_state(sa);
    SdpdBackend b;
    b.initialize(s.model, s.state, {});
    b.restore(blob);
    b.advance(1, 0.03);
    ParticleState sb;
    b.read_state(sb);
    const char* what = wall_model_name(wm);
    EXPECT_EQ(sa.positions, sb.positions) << what;
    EXPECT_EQ(sa.velocities, sb.velocities) << what;
    EXPECT_EQ(sa.densities, sb.densities) << what;
    EXPECT_LT(deviation(s, sb, b.time()), 1e-12) << what;
  }
}

TEST(MovingBodies, RefusedByOtherBackendsAndWithMorrisWalls) {
  test::DiskInBox s = moving_disk(2, 10, WallModel::kStationary, {1.0, 0.0, 0.0}, 0.0);
  s.model.body_forces.clear();
  BackendRegistry registry;
  register_builtin_backends(registry);
  auto stat = registry.create("static");
  try {
    stat->initialize(s.model, s.state, {});
    FAIL() << "static accepted a moving body";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("moving_bodies"), std::string::npos) << e.what();
  }
  // Morris: the regions' surfaces stay in place, tangent planes do not turn
  test::DiskInBox m = moving_disk(2, 10, WallModel::kMorrisExtrapolated, {1.0, 0.0, 0.0}, 0.0);
  SdpdBackend b;
  try {
    b.initialize(m.model, m.state, {});
    FAIL() << "Morris walls on a region surface accepted a moving body";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("wall_model"), std::string::npos) << e.what();
  }
  test::DiskInBox turning =
      moving_disk(2, 10, WallModel::kMorrisExtrapolated, {1.0, 0.0, 0.0}, 1.0);
  turning.model.wall_regions.clear();
  add_tangents(turning);
  try {
    b.initialize(turning.model, turning.state, {});
    FAIL() << "Morris walls accepted a turning body";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("angular_velocity"), std::string::npos) << e.what();
  }
  turning.model.moving_bodies.front().motion.angular_velocity = 0.0;
  EXPECT_NO_THROW(b.initialize(turning.model, turning.state, {}));  // translating: allowed
}

TEST(MovingBodies, LeavingTheBoxOnAWalledAxisStopsTheRun) {
  test::DiskInBox s = moving_disk(2, 20, WallModel::kStationary, {-5.0, 0.0, 0.0}, 0.0);
  s.model.box.periodic[0] = false;
  // no fluid between the disk and the face x = 0, so the disk's walls reach it first
  ParticleState p;
  p.dimension = 2;
  std::vector<std::uint32_t> walls;
  for (std::size_t i = 0; i < s.state.size(); ++i) {
    if (s.state.kind(i) == ParticleKind::kFluid && s.state.positions[3 * i] < 0.3) continue;
    if (s.state.kind(i) == ParticleKind::kWall)
      walls.push_back(static_cast<std::uint32_t>(p.size()));
    p.positions.insert(p.positions.end(), &s.state.positions[3 * i], &s.state.positions[3 * i] + 3);
    p.velocities.insert(p.velocities.end(), {0.0, 0.0, 0.0});
    p.kinds.push_back(s.state.kinds[i]);
    p.masses.push_back(s.state.masses[i]);
    p.densities.push_back(s.state.densities[i]);
  }
  s.model.moving_bodies.front().particles = walls;
  s.model.body_forces.front().particles = walls;
  SdpdBackend b;
  b.initialize(s.model, p, {});
  try {
    for (std::uint64_t k = 0; k < 10; ++k) b.advance(k, 0.01);
    FAIL() << "the disk left the box and the run went on";
  } catch (const NumericalFailure& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("moving body 'disk' reaches beyond the box on a walled axis at t = "),
              std::string::npos)
        << m;
  }
}

}  // namespace
}  // namespace sadr::fluid
