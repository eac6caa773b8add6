// SPDX-License-Identifier: MIT
/// \file taylor_couette_scene.hpp
/// Steady Taylor-Couette flow between an inner cylinder spinning at kOmega and a fixed outer one
/// (2D annulus R1 < r < R2 on a square lattice, gap/dx = 10), and its exact profile
/// u_theta = A r + B/r (tests of moving walls and moving bodies).
#pragma once

#include <cmath>
#include <cstdint>

#include "sadr/fluid/fluid_model.hpp"

namespace sadr::fluid::test {

inline constexpr double kR1 = 0.5, kR2 = 1.0, kOmega = 2.0, kNuTc = 0.2, kDxTc = 0.05;

inline double taylor_couette_exact(double r) {
  const double a = -kOmega * kR1 * kR1 / (kR2 * kR2 - kR1 * kR1);
  const double b = kOmega * kR1 * kR1 * kR2 * kR2 / (kR2 * kR2 - kR1 * kR1);
  return a * r + b / r;
}

/// A square lattice (spacing kDxTc) on the annulus R1 < r < R2 about the origin, 3 wall layers
/// inside R1 (spinning: Omega z x x) and outside R2 (at rest); with Morris walls each wall
/// particle's tangent plane (the circle's, at its closest surface point).
inline ParticleState taylor_couette_particles(FluidModel& m) {
  const double h = 3.0 * kDxTc, reach = kR2 + h + kDxTc;
  m.box.dimension = 2;
  m.box.lo = {-reach, -reach, 0};
  m.box.hi = {reach, reach, 1};
  m.box.periodic = {false, false, false};
  ParticleState p;
  p.dimension = 2;
  const int n = static_cast<int>(std::ceil(reach / kDxTc));
  for (int ky = -n; ky < n; ++ky) {
    for (int kx = -n; kx < n; ++kx) {
      const double x = (kx + 0.5) * kDxTc, y = (ky + 0.5) * kDxTc, r = std::hypot(x, y);
      if (r <= kR1 - h || r >= kR2 + h) continue;
      const bool inner = r<kR1, outer = r> kR2;
      const auto i = static_cast<std::uint32_t>(p.kinds.size());
      p.positions.insert(p.positions.end(), {x, y, 0.0});
      p.velocities.insert(p.velocities.end(),
                          {inner ? -kOmega * y : 0.0, inner ? kOmega * x : 0.0, 0.0});
      p.kinds.push_back(inner || outer ? ParticleKind::kWall : ParticleKind::kFluid);
      p.masses.push_back(kDxTc * kDxTc);
      p.densities.push_back(1.0);
      if (inner || outer) {
        m.wall_tangents.particles.push_back(i);
        m.wall_tangents.depths.push_back(inner ? kR1 - r : r - kR2);
        const double s = inner ? 1.0 : -1.0;  // into the fluid
        m.wall_tangents.normals.insert(m.wall_tangents.normals.end(), {s * x / r, s * y / r, 0.0});
      }
    }
  }
  p.ids.resize(p.kinds.size());
  for (std::size_t i = 0; i < p.ids.size(); ++i) p.ids[i] = i;
  return p;
}

}  // namespace sadr::fluid::test
