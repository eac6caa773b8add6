// SPDX-License-Identifier: MIT
/// \file boundary_share.hpp
/// Where a boundary flux (scene `boundary_fluxes`) enters: the first layer of fluid particles at
/// a box face or at a surface of the scene's geometry, and each one's share A_i of the face's or
/// surface's area (docs/method.md 4d).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "sadr/common/particle_state.hpp"
#include "sadr/orchestrator/region.hpp"

namespace sadr::orchestrator {

struct BoundaryShare {
  std::vector<std::uint32_t> particles;  ///< the first fluid layer at the face, ascending
  std::vector<double> areas;             ///< A_i [length^(d-1)], parallel to particles
  double area = 0;                       ///< A: the face's area inside the region
  /// Surfaces only: the layer's own estimate of the area, sum_i l_i^(d-1) [length^(d-1)].
  double layer_area = 0;
};

/// The face is axis `axis`'s lower (`upper` false) or upper box face; `extent` (a box or channel
/// region, or nullptr) restricts it along the other axes: A = prod_t |[lo_t, hi_t] of the box
/// and the region| (1 in 1D). Candidates are the fluid particles whose tangential coordinates
/// lie on that patch (within `tol`); the first layer is those within l_i / 2 (l_i = V_i^(1/d))
/// of the outermost candidate along the normal. A_i = A l_i^(d-1) / sum_j l_j^(d-1), so
/// sum_i A_i = A to round-off (checked to 1e-12 A). Throws InvalidArgument for an empty patch
/// or no fluid particle on it.
[[nodiscard]] BoundaryShare boundary_share(const ParticleState& particles, const Box& box, int axis,
                                           bool upper, const Region* extent, double tol);

/// The first fluid layer next to surface `surface` of a geometry (GeometryReport::surface_id):
/// candidates are the fluid particles whose nearest surface is that one (surface_id[i] ==
/// surface, distance[i] finite); with d_min the smallest of their distances, the layer is those
/// with distance[i] < d_min + (1 - 1e-9) `spacing` (a shell one lattice spacing thick, which
/// holds exactly one lattice row next to a plane surface). A_i = A l_i^(d-1) / sum_j l_j^(d-1)
/// (l_i = V_i^(1/d)); A is `area`, or without it the layer's estimate sum_j l_j^(d-1). A
/// non-empty `part` (one entry per particle) keeps only the candidates i with part[i] != 0 (a
/// part of the surface: the layer and d_min are then the part's). Throws InvalidArgument when
/// no fluid particle lies next to the surface (or its part).
[[nodiscard]] BoundaryShare surface_share(const ParticleState& particles,
                                          std::span<const int> surface_id,
                                          std::span<const double> distance, int surface,
                                          double spacing, std::optional<double> area,
                                          std::span<const std::uint8_t> part = {});

}  // namespace sadr::orchestrator
