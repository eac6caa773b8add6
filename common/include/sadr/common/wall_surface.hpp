// SPDX-License-Identifier: MIT
/// \file wall_surface.hpp
/// The wall surface of a group of wall particles and the Morris, Fox & Zhu (1997) extrapolation
/// factor across it: the one home of this geometry, used by the SDPD backend (velocity and
/// Dirichlet species, fluid_service/backends/sdpd/sdpd_morris_walls.hpp) and by the SSA
/// (Dirichlet reservoirs, ssa_service/core/src/wall_surfaces.cpp); docs/method.md section 2 and 4.
///
/// For a pair of a fluid particle i at distance d_i in front of the surface and a wall particle j
/// at depth d_j behind it, the wall value is extrapolated linearly through the held value on the
/// surface: phi_j' = phi_w + (phi_w - phi_i) d_j / d_i, so that the pair term (phi_j' - phi_i) is
/// beta (phi_w - phi_i) with beta = 1 + d_j / d_i, capped at 1.5 (Morris et al.) and with d_i
/// floored at 1e-3 h.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

namespace sadr {

/// A plane (radius == 0) through `point` with unit normal `inward_normal` pointing into the fluid,
/// or (radius > 0) a circle (2D) / sphere (3D) of that radius around `point`, the fluid outside.
struct WallSurface {
  std::array<double, 3> point{0, 0, 0};          ///< [length]
  std::array<double, 3> inward_normal{1, 0, 0};  ///< unit; planes only
  double radius = 0.0;                           ///< [length]

  /// Distance of x (3 doubles) from the surface, positive on the fluid side [length].
  [[nodiscard]] double signed_distance(const double* x) const {
    double d = 0;
    if (radius > 0) {
      for (int a = 0; a < 3; ++a) d += (x[a] - point[a]) * (x[a] - point[a]);
      return std::sqrt(d) - radius;
    }
    for (int a = 0; a < 3; ++a) d += inward_normal[a] * (x[a] - point[a]);
    return d;
  }
  /// Depth of a wall particle at x behind the surface (0 if it lies on the fluid side) [length].
  [[nodiscard]] double depth(const double* x) const { return std::max(-signed_distance(x), 0.0); }
};

/// Morris beta of a fluid particle at signed distance `distance` in front of the surface and a
/// wall particle at `depth` behind it, for the kernel support h: min(1.5, 1 + depth /
/// max(distance, 1e-3 h)).
[[nodiscard]] inline double morris_beta(double depth, double distance, double h) {
  return std::min(1.5, 1.0 + depth / std::max(distance, 1e-3 * h));
}

}  // namespace sadr
