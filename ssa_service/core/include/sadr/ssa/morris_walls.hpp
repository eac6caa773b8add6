// SPDX-License-Identifier: MIT
/// \file morris_walls.hpp
/// Morris-extrapolated Dirichlet walls on the diffusion graph (Model::morris_walls,
/// docs/method.md section 4): the edges between non-wall voxels and wall voxels that have a wall
/// surface are scaled by beta (common/wall_surface.hpp) in both directions.
#pragma once

#include <cstdint>
#include <vector>

#include "sadr/common/particle_state.hpp"
#include "sadr/ssa/diffusion_graph.hpp"
#include "sadr/ssa/model.hpp"

namespace sadr::ssa {

/// Index into model.morris_walls of every voxel (-1: none, and for every non-wall voxel); the
/// first MorrisWall listing a wall voxel wins. A wall voxel with a tangent plane (entry k of
/// model.morris_tangents) gets morris_walls.size() + k. Throws InvalidArgument for an index >= N.
[[nodiscard]] std::vector<std::int32_t> assign_morris_walls(const Model& model,
                                                            const DiffusionGraph& g);

/// Scales, for the graph g just built from `particles`, the weight of every edge i -> j and
/// j -> i between a non-wall voxel i and a wall voxel j with surface[j] >= 0 (from
/// assign_morris_walls) by beta_ij = morris_beta(depth of j, distance of i, h) (from j's region
/// surface, or from j's tangent plane and the minimum-image x_i - x_j), and recomputes
/// sum_all / sum_nowall of the rows it touched. Both directions get the same bits of beta.
void apply_morris_walls(DiffusionGraph& g, const Model& model, const ParticleState& particles,
                        const std::vector<std::int32_t>& surface);

}  // namespace sadr::ssa
