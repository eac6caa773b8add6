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
///
/// Walls made by a scene's geometry carry one surface per wall particle instead (WallTangents):
/// the tangent plane at the particle's closest surface point.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

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

/// Per-particle wall surfaces (Morris walls made by a scene's geometry): wall particle
/// particles[k] at x_j sits depths[k] behind its own tangent plane, the plane through its closest
/// surface point x_j + depth_j n_j with the unit normal n_j = normals[3k..3k+2] pointing into the
/// fluid. A point at displacement r = x - x_j from the wall particle is n_j . r - depth_j in front
/// of that plane: exact for a plane, within about s^2 / (2 R) of the distance to a surface of
/// curvature radius R for a point whose foot lies s from the particle's closest surface point.
/// Empty (the default) when the walls have no such surfaces.
struct WallTangents {
  std::vector<std::uint32_t> particles;  ///< wall particle indices (into the initial state)
  std::vector<double> depths;            ///< depth_j >= 0 behind the plane [length]
  std::vector<double> normals;           ///< n_j, 3 per particle, unit

  [[nodiscard]] bool empty() const { return particles.empty(); }
  [[nodiscard]] std::size_t size() const { return particles.size(); }
  /// Signed distance in front of entry k's plane of the point at displacement r (3 doubles, the
  /// inactive axes 0) from its wall particle [length].
  [[nodiscard]] double signed_distance(std::size_t k, const double* r) const {
    const double* n = &normals[3 * k];
    return n[0] * r[0] + n[1] * r[1] + n[2] * r[2] - depths[k];
  }
  /// Entry k as a WallSurface (a plane), for the wall particle at x_j (3 doubles).
  [[nodiscard]] WallSurface plane(std::size_t k, const double* xj) const {
    WallSurface s;
    for (std::size_t a = 0; a < 3; ++a) {
      s.inward_normal[a] = normals[3 * k + a];
      s.point[a] = xj[a] + depths[k] * normals[3 * k + a];
    }
    return s;
  }
  /// The problems of the arrays, each naming its field (empty: none): sizes, a particle index
  /// >= n (pass SIZE_MAX when n is not known) or listed twice, a depth not finite or < 0, a normal
  /// not of unit length.
  [[nodiscard]] std::vector<std::string> problems(std::size_t n) const {
    std::vector<std::string> out;
    if (depths.size() != particles.size() || normals.size() != 3 * particles.size()) {
      out.push_back("wall_tangents: " + std::to_string(particles.size()) + " particles, " +
                    std::to_string(depths.size()) + " depths, " + std::to_string(normals.size()) +
                    " normal components (allowed: 1 depth and 3 components per particle)");
      return out;
    }
    std::vector<std::uint32_t> sorted = particles;
    std::sort(sorted.begin(), sorted.end());
    const auto twice = std::adjacent_find(sorted.begin(), sorted.end());
    if (twice != sorted.end()) {
      out.push_back("wall_tangents: particle " + std::to_string(*twice) + " is listed twice");
    }
    for (std::size_t k = 0; k < particles.size(); ++k) {
      const std::string at = "wall_tangents[" + std::to_string(k) + "]";
      const std::uint32_t j = particles[k];
      if (j >= n) {
        out.push_back(at + ".particle = " + std::to_string(j) + " (allowed: 0.." +
                      std::to_string(static_cast<long>(n) - 1) + ")");
      }
      if (!(std::isfinite(depths[k]) && depths[k] >= 0)) {
        out.push_back(at + ".depth is not finite and >= 0");
      }
      const double* v = &normals[3 * k];
      const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      if (!(std::abs(len - 1.0) < 1e-6)) {
        out.push_back(at + ".normal has length " + std::to_string(len) + " (allowed: unit)");
      }
      if (out.size() >= 10) break;  // enough to see what is wrong
    }
    return out;
  }
};

}  // namespace sadr
