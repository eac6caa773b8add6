// SPDX-License-Identifier: MIT
/// \file disk_in_box_scene.hpp
/// A periodic unit box of n^d lattice cells with a solid disk (2D) or sphere (3D) of radius r at
/// its centre made of wall particles (the sites within r, less those deeper than h behind the
/// surface), driven by the body acceleration g along x; the body is FluidModel::body_forces[0]
/// "disk" (tests of the forces on bodies).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "sadr/fluid/fluid_model.hpp"

namespace sadr::fluid::test {

struct DiskInBox {
  FluidModel model;
  ParticleState state;
};

inline DiskInBox disk_in_box(int dim, int n, WallModel wm, double radius, double eta, double g,
                             double sound_speed = 1.0) {
  DiskInBox s;
  const double dx = 1.0 / n, h = 3.0 * dx;
  s.model.box.dimension = dim;
  for (int a = 0; a < 3; ++a) {
    s.model.box.lo[a] = 0;
    s.model.box.hi[a] = 1;
    s.model.box.periodic[a] = a < dim;
  }
  s.model.smoothing_length = h;
  s.model.kernel = "wendland_c2";
  s.model.sound_speed = sound_speed;
  s.model.shear_viscosity = eta;
  s.model.gravity = {g, 0.0, 0.0};
  s.model.wall_model = wm;
  ParticleState& p = s.state;
  p.dimension = dim;
  const double vol = std::pow(dx, dim);
  BodyForceGroup body{"disk", {}};
  const int nz = dim == 3 ? n : 1;
  for (int kz = 0; kz < nz; ++kz) {
    for (int ky = 0; ky < n; ++ky) {
      for (int kx = 0; kx < n; ++kx) {
        const std::array<double, 3> x{(kx + 0.5) * dx, (ky + 0.5) * dx,
                                      dim == 3 ? (kz + 0.5) * dx : 0.0};
        double r2 = 0;
        for (int a = 0; a < dim; ++a) r2 += (x[a] - 0.5) * (x[a] - 0.5);
        const double r = std::sqrt(r2);
        if (r < radius - h) continue;  // out of the fluid's reach
        const bool wall = r < radius;
        if (wall) body.particles.push_back(static_cast<std::uint32_t>(p.size()));
        p.positions.insert(p.positions.end(), x.begin(), x.end());
        p.kinds.push_back(wall ? ParticleKind::kWall : ParticleKind::kFluid);
        p.masses.push_back(vol);
        p.densities.push_back(1.0);
      }
    }
  }
  p.velocities.assign(3 * p.size(), 0.0);
  if (wm == WallModel::kMorrisExtrapolated) {
    WallRegion w;
    w.name = "disk";
    w.particles = body.particles;
    w.surface_point = {0.5, 0.5, dim == 3 ? 0.5 : 0.0};
    w.surface_radius = radius;
    s.model.wall_regions.push_back(w);
  }
  s.model.body_forces.push_back(body);
  return s;
}

}  // namespace sadr::fluid::test
