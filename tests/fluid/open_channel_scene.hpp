// SPDX-License-Identifier: MIT
// A 2D open channel for the SDPD open-boundary tests: walls along y (4 layers) over the whole
// length, inlet buffer, fluid, outlet buffer along x (not periodic). Reduced units: H = 1.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "sadr/fluid/fluid_model.hpp"
#include "sdpd/sdpd_backend.hpp"

namespace sadr::fluid::test {

struct OpenChannelSpec {
  int ny = 10;               ///< fluid rows; dx = H/ny
  double length = 3.0;       ///< fluid part L [H]
  int buffer_columns = 4;    ///< Lb = buffer_columns dx (>= h = 3 dx)
  double mean_velocity = 1;  ///< U
  double nu = 0.1;           ///< kinematic viscosity (eta = rho nu, rho = 1)
  double sound_speed = 15;   ///< c0 = 10 u_max
  bool parabolic = true;
  bool start_with_profile = false;  ///< fluid starts at the inflow profile (else at rest)
  double temperature = 0.0;
};

struct OpenChannel {
  FluidModel model;
  ParticleState particles;
  double dx = 0;
};

inline OpenChannel make_open_channel(const OpenChannelSpec& s) {
  OpenChannel c;
  const double H = 1.0, dx = H / s.ny, lb = s.buffer_columns * dx;
  c.dx = dx;
  const int nx = static_cast<int>(std::lround(s.length / dx)) + 2 * s.buffer_columns;
  const int wl = 4;
  FluidModel& m = c.model;
  m.box.dimension = 2;
  m.box.lo = {-lb, -wl * dx, 0};
  m.box.hi = {s.length + lb, H + wl * dx, 1};
  m.box.periodic = {false, false, false};
  m.smoothing_length = 3 * dx;
  m.reference_density = 1.0;
  m.sound_speed = s.sound_speed;
  m.shear_viscosity = s.nu;
  m.temperature = s.temperature;
  m.seed = 11;
  auto& ob = m.open_boundary;
  ob.enabled = true;
  ob.axis = 0;
  ob.inlet_lo = -lb;
  ob.fluid_lo = 0;
  ob.fluid_hi = s.length;
  ob.outlet_hi = s.length + lb;
  ob.profile = s.parabolic ? OpenBoundary::Profile::kParabolic : OpenBoundary::Profile::kUniform;
  ob.mean_velocity = s.mean_velocity;
  ob.cross_axis = 1;
  ob.wall_lo = 0;
  ob.wall_hi = H;
  ParticleState& p = c.particles;
  p.dimension = 2;
  for (int j = -wl; j < s.ny + wl; ++j) {
    for (int i = 0; i < nx; ++i) {
      const double x[3] = {-lb + (i + 0.5) * dx, (j + 0.5) * dx, 0.0};
      const bool wall = j < 0 || j >= s.ny;
      p.positions.insert(p.positions.end(), x, x + 3);
      const ParticleKind k = wall              ? ParticleKind::kWall
                             : x[0] < 0        ? ParticleKind::kInlet
                             : x[0] < s.length ? ParticleKind::kFluid
                                               : ParticleKind::kOutlet;
      p.kinds.push_back(k);
      p.masses.push_back(dx * dx);
      p.densities.push_back(1.0);
      const double u =
          (!wall && (s.start_with_profile || k == ParticleKind::kInlet)) ? ob.inflow_speed(x) : 0.0;
      p.velocities.insert(p.velocities.end(), {u, 0.0, 0.0});
    }
  }
  p.ids.resize(p.densities.size());
  for (std::size_t i = 0; i < p.ids.size(); ++i) p.ids[i] = i;
  return c;
}

/// Transition counts between two states of the same particles (by index).
struct Crossings {
  std::uint64_t in = 0;        ///< inlet -> fluid
  std::uint64_t out = 0;       ///< fluid -> outlet
  std::uint64_t recycled = 0;  ///< outlet -> inlet
};

inline void count_crossings(const ParticleState& before, const ParticleState& after, Crossings& c) {
  for (std::size_t i = 0; i < after.size(); ++i) {
    const ParticleKind a = before.kind(i), b = after.kind(i);
    if (a == ParticleKind::kInlet && b == ParticleKind::kFluid) ++c.in;
    if (a == ParticleKind::kFluid && b == ParticleKind::kOutlet) ++c.out;
    if (a == ParticleKind::kOutlet && b == ParticleKind::kInlet) ++c.recycled;
  }
}

}  // namespace sadr::fluid::test
