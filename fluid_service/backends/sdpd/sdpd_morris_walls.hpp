// SPDX-License-Identifier: MIT
/// \file sdpd_morris_walls.hpp
/// Morris, Fox & Zhu (1997) extrapolated wall velocity for the SDPD backend
/// (WallModel::kMorrisExtrapolated, docs/fluid-core.md): in the viscous term of a pair of a fluid
/// particle i and a wall particle j of a planar WallRegion, the wall velocity is -(d_j/d_i) v_i,
/// i.e. v_ij = beta v_i with beta = min(1.5, 1 + d_j / max(d_i, 1e-3 h)), d the distance to the
/// region's wall surface (d_j behind it, d_i in front): a plane, or a circle / sphere with the
/// fluid outside (WallRegion::surface_radius > 0). The pressure term keeps v_j = 0. The geometry
/// (distances, beta) is common/wall_surface.hpp, shared with the SSA's Dirichlet reservoirs.
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
  /// (FluidModel::assign_wall_regions) and its depth behind the region's plane.
  void setup(const FluidModel& model, const ParticleState& initial) {
    enabled_ = model.wall_model == WallModel::kMorrisExtrapolated;
    surfaces_.clear();
    for (const auto& reg : model.wall_regions) surfaces_.push_back(reg.surface());
    const std::size_t n = initial.size();
    region_.assign(n, -1);
    depth_.assign(n, 0.0);
    if (!enabled_) return;
    region_ = model.assign_wall_regions(initial);
    for (std::size_t i = 0; i < n; ++i) {
      const int w = region_[i];
      if (w < 0) continue;
      depth_[i] = surfaces_[static_cast<std::size_t>(w)].depth(&initial.positions[3 * i]);
    }
  }
  [[nodiscard]] bool enabled() const { return enabled_; }
  /// Whether wall particle j extrapolates the velocity (it belongs to a region).
  [[nodiscard]] bool extrapolates(std::uint32_t j) const { return region_[j] >= 0; }
  /// beta of the pair of the fluid particle at xi with wall particle j (extrapolates(j)), for
  /// the kernel support h.
  [[nodiscard]] double beta(const double* xi, std::uint32_t j, double h) const {
    const auto& surface = surfaces_[static_cast<std::size_t>(region_[j])];
    return morris_beta(depth_[j], surface.signed_distance(xi), h);
  }
  [[nodiscard]] std::size_t bytes() const {
    return region_.capacity() * sizeof(std::int32_t) + depth_.capacity() * sizeof(double);
  }

 private:
  bool enabled_ = false;
  std::vector<WallSurface> surfaces_;  ///< per WallRegion
  std::vector<std::int32_t> region_;   ///< wall particle -> WallRegion index (-1: none)
  std::vector<double> depth_;          ///< distance of a wall particle behind its plane [length]
};

}  // namespace sadr::fluid
