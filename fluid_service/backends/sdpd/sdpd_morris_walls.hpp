// SPDX-License-Identifier: MIT
/// \file sdpd_morris_walls.hpp
/// Morris, Fox & Zhu (1997) extrapolated wall velocity for the SDPD backend
/// (WallModel::kMorrisExtrapolated, docs/fluid-core.md): in the viscous term of a pair of a fluid
/// particle i and a wall particle j of a planar WallRegion, the wall velocity is -(d_j/d_i) v_i,
/// i.e. v_ij = beta v_i with beta = min(1.5, 1 + d_j / max(d_i, 1e-3 h)), d the distance to the
/// region's wall surface (d_j behind it, d_i in front): a plane, or a circle / sphere with the
/// fluid outside (WallRegion::surface_radius > 0), or, with walls made by a scene's geometry
/// (FluidModel::wall_tangents), wall particle j's own tangent plane: d_j its depth, d_i the
/// distance of i in front of it from the pair's (minimum-image) displacement. The pressure term
/// keeps v_j = 0. The geometry (distances, beta) is common/wall_surface.hpp, shared with the
/// SSA's Dirichlet reservoirs.
#pragma once

#include <cstdint>
#include <vector>

#include "sadr/common/particle_state.hpp"
#include "sadr/common/wall_surface.hpp"
#include "sadr/fluid/fluid_model.hpp"

namespace sadr::fluid {

class MorrisWalls {
 public:
  /// Off unless model.wall_model is kMorrisExtrapolated; else the region of every wall particle
  /// (FluidModel::assign_wall_regions) and its depth behind the region's plane, or, with
  /// model.wall_tangents, every listed wall particle's tangent plane.
  void setup(const FluidModel& model, const ParticleState& initial) {
    enabled_ = model.wall_model == WallModel::kMorrisExtrapolated;
    surfaces_.clear();
    for (const auto& reg : model.wall_regions) surfaces_.push_back(reg.surface());
    const std::size_t n = initial.size();
    region_.assign(n, -1);
    depth_.assign(n, 0.0);
    tangent_.clear();
    normal_.clear();
    if (!enabled_) return;
    if (!model.wall_tangents.empty()) {
      const WallTangents& t = model.wall_tangents;
      tangent_.assign(n, -1);
      normal_ = t.normals;
      for (std::size_t k = 0; k < t.size(); ++k) {
        const std::uint32_t j = t.particles[k];
        if (j >= n || initial.kind(j) != ParticleKind::kWall) continue;
        tangent_[j] = static_cast<std::int32_t>(k);
        depth_[j] = t.depths[k];
      }
      return;
    }
    region_ = model.assign_wall_regions(initial);
    for (std::size_t i = 0; i < n; ++i) {
      const int w = region_[i];
      if (w < 0) continue;
      depth_[i] = surfaces_[static_cast<std::size_t>(w)].depth(&initial.positions[3 * i]);
    }
  }
  [[nodiscard]] bool enabled() const { return enabled_; }
  /// Whether wall particle j extrapolates the velocity (it belongs to a region, or has a
  /// tangent plane).
  [[nodiscard]] bool extrapolates(std::uint32_t j) const {
    return tangent_.empty() ? region_[j] >= 0 : tangent_[j] >= 0;
  }
  /// beta of the pair of the fluid particle at xi with wall particle j (extrapolates(j)), their
  /// displacement xij = x_i - x_j (D values, minimum image), for the kernel support h.
  template <int D>
  [[nodiscard]] double beta(const double* xi, const double* xij, std::uint32_t j, double h) const {
    if (!tangent_.empty()) {
      const double* nj = &normal_[3 * static_cast<std::size_t>(tangent_[j])];
      double di = -depth_[j];
      for (int a = 0; a < D; ++a) di += nj[a] * xij[a];
      return morris_beta(depth_[j], di, h);
    }
    return beta(xi, j, h);
  }
  /// The same for a wall particle j of a region (no tangent planes).
  [[nodiscard]] double beta(const double* xi, std::uint32_t j, double h) const {
    const auto& surface = surfaces_[static_cast<std::size_t>(region_[j])];
    return morris_beta(depth_[j], surface.signed_distance(xi), h);
  }
  [[nodiscard]] std::size_t bytes() const {
    return region_.capacity() * sizeof(std::int32_t) + depth_.capacity() * sizeof(double) +
           tangent_.capacity() * sizeof(std::int32_t) + normal_.capacity() * sizeof(double);
  }

 private:
  bool enabled_ = false;
  std::vector<WallSurface> surfaces_;  ///< per WallRegion
  std::vector<std::int32_t> region_;   ///< wall particle -> WallRegion index (-1: none)
  std::vector<double> depth_;          ///< distance of a wall particle behind its plane [length]
  std::vector<std::int32_t> tangent_;  ///< wall particle -> WallTangents entry (empty: regions)
  std::vector<double> normal_;         ///< WallTangents::normals
};

}  // namespace sadr::fluid
