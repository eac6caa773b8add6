// SPDX-License-Identifier: MIT
// Property (physics): Galilean invariance of a moving body's drag (FluidModel::moving_bodies;
// docs/fluid-core.md "Moving walls"; a turning body against Taylor-Couette flow:
// sdpd_moving_bodies_taylor_couette_test.cpp). The periodic cylinder array of the
// drag validation (cylinder_array_validation_test.cpp: a disk of solid fraction c = 0.1 in a unit
// cell, fluid driven by the body acceleration g along x, Adami walls) at 20 particles across, run
// twice to t = 0.6 (about 13 relaxation times):
//  A: the disk at rest, the fluid from rest;
//  B: the disk translating at (-1, -0.5) (it crosses 0.6 of the cell, 12 spacings, along x and
//     0.3 across; its walls move normal to their surface at its front and back), the fluid
//     starting at the same velocity.
// Seen from the disk, B is A, so at steady state the force on the disk must be the same (= M g,
// the fluid's weight under g, F/(M g) - 1 as in the validation) and so must the flow relative to
// the disk: the superficial velocity sum m (v_x + U) / rho_0. The pair terms see relative
// positions and velocity differences only, and the two runs take the same sub-steps, so they
// agree to round-off: this checks that the backend's placement of the walls, their velocities in
// every wall model term and the neighbour lists at the moved positions are those of the fixed
// disk seen from a moving frame.
// The force across the flow and the torque about the body's (moving) centroid agree too. Every
// frame (every 0.02) no fluid particle lies inside the disk's surface, counted at the disk's
// current centre. Prints RESULT lines.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "disk_in_box_scene.hpp"
#include "sdpd/sdpd_backend.hpp"

namespace sadr::fluid {
namespace {

constexpr double kC = 0.1, kEta = 1.0, kG = 1.0, kC0 = 20.0, kU = 1.0, kV = 0.5;
constexpr int kN = 20;

struct DragRun {
  double force = 0, flux = 0, balance = 0, force_y = 0, torque = 0;
  int inside_half = 0;  ///< max over frames: fluid particles more than dx/2 inside the surface
  int inside = 0;       ///< max over frames: fluid particles inside the surface
};

DragRun run(bool moving, WallModel wm) {
  const double radius = std::sqrt(kC / std::numbers::pi);
  test::DiskInBox s = test::disk_in_box(2, kN, wm, radius, kEta, kG, kC0);
  if (wm == WallModel::kMorrisExtrapolated) {  // the geometry's way: a tangent plane per particle
    s.model.wall_regions.clear();
    for (const std::uint32_t i : s.model.body_forces.front().particles) {
      const double x = s.state.positions[3 * i] - 0.5, y = s.state.positions[3 * i + 1] - 0.5;
      const double r = std::hypot(x, y);
      if (!(r > 0)) continue;
      s.model.wall_tangents.particles.push_back(i);
      s.model.wall_tangents.depths.push_back(radius - r);
      s.model.wall_tangents.normals.insert(s.model.wall_tangents.normals.end(),
                                           {x / r, y / r, 0.0});
    }
  }
  const double u0 = moving ? -kU : 0.0, v0 = moving ? -kV : 0.0;
  if (moving) {
    MovingBody body;
    body.name = "disk";
    body.particles = s.model.body_forces.front().particles;
    body.motion.velocity = {u0, v0, 0.0};
    body.motion.center = {0.5, 0.5, 0.0};
    s.model.moving_bodies.push_back(body);
    for (std::size_t i = 0; i < s.state.size(); ++i) {
      s.state.velocities[3 * i] = u0;
      s.state.velocities[3 * i + 1] = v0;
    }
  }
  SdpdBackend b;
  b.initialize(s.model, s.state, {});
  constexpr double kTau = 0.02, kEnd = 0.6, kAverageFrom = 0.4;
  const double dx = 1.0 / kN;
  const int steps = static_cast<int>(std::lround(kEnd / kTau));
  DragRun out;
  double f_sum = 0, fy_sum = 0, t_sum = 0, u_sum = 0, mass = 0;
  int samples = 0;
  for (int k = 0; k < steps; ++k) {
    const StepReport rep = b.advance(static_cast<std::uint64_t>(k), kTau);
    ParticleState st;
    b.read_state(st);
    const double cx = 0.5 + u0 * rep.time, cy = 0.5 + v0 * rep.time;
    int inside = 0, inside_half = 0;
    double px = 0;
    mass = 0;
    for (std::size_t i = 0; i < st.size(); ++i) {
      if (st.kind(i) != ParticleKind::kFluid) continue;
      double dxc = st.positions[3 * i] - cx, dyc = st.positions[3 * i + 1] - cy;
      dxc -= std::round(dxc);
      dyc -= std::round(dyc);
      const double r = std::hypot(dxc, dyc);
      inside += r < radius ? 1 : 0;
      inside_half += r < radius - 0.5 * dx ? 1 : 0;
      px += st.masses[i] * (st.velocities[3 * i] - u0);
      mass += st.masses[i];
    }
    out.inside = std::max(out.inside, inside);
    out.inside_half = std::max(out.inside_half, inside_half);
    if (rep.time < kAverageFrom + 1e-9) continue;
    f_sum += rep.body_forces.at(0).force[0];
    fy_sum += rep.body_forces.at(0).force[1];
    t_sum += rep.body_forces.at(0).torque[2];
    u_sum += px / s.model.reference_density;
    ++samples;
  }
  out.force = f_sum / samples;
  out.flux = u_sum / samples;
  out.force_y = fy_sum / samples;
  out.torque = t_sum / samples;
  out.balance = out.force / (mass * kG) - 1.0;
  return out;
}

void check_galilean(WallModel wm) {
  const DragRun a = run(false, wm), b = run(true, wm);
  const double df = b.force / a.force - 1.0, du = b.flux / a.flux - 1.0;
  const double radius = std::sqrt(kC / std::numbers::pi);
  // the torque about the body's moving centroid: a reference left at t = 0 would add about
  // (0.25 across the flow, the mean over the samples) x F = 1.4 F R
  const double dt = (b.torque - a.torque) / (a.force * radius);
  const double dfy = (b.force_y - a.force_y) / a.force;
  std::printf(
      "RESULT moving_body_drag walls=%s n=%d fixed: F=%.6f F/(Mg)-1=%+.2e flux=%.6f | moving (%g, "
      "%g): "
      "F=%.6f F/(Mg)-1=%+.2e flux=%.6f | dF/F=%+.2e dflux/flux=%+.2e dFy/F=%+.2e "
      "dT/(F R)=%+.2e | fluid inside the disk (max per frame) fixed %d / moving %d, deeper than "
      "dx/2: %d / %d\n",
      wall_model_name(wm), kN, a.force, a.balance, a.flux, -kU, -kV, b.force, b.balance, b.flux, df,
      du, dfy, dt, a.inside, b.inside, a.inside_half, b.inside_half);
  EXPECT_LT(std::fabs(a.balance), 2e-3);  // steady
  EXPECT_LT(std::fabs(b.balance), 2e-3);
  // the same sub-steps, so the same flow to round-off
  EXPECT_LT(std::fabs(df), 1e-9);
  EXPECT_LT(std::fabs(du), 1e-9);
  EXPECT_LT(std::fabs(dfy), 1e-9);
  EXPECT_LT(std::fabs(dt), 1e-9);
  EXPECT_EQ(b.inside, 0);
  EXPECT_EQ(a.inside, 0);
}

TEST(MovingBodies, TranslatingCylinderArrayHasTheDragOfTheFixedOne) {
  check_galilean(WallModel::kAdami);
  check_galilean(WallModel::kStationary);
  check_galilean(WallModel::kMorrisExtrapolated);  // with the tangent planes
}

}  // namespace
}  // namespace sadr::fluid
