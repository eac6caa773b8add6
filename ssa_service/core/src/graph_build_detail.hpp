// SPDX-License-Identifier: MIT
/// \file graph_build_detail.hpp
/// Pieces of the graph build shared by DiffusionGraph::build_into() and
/// GraphBuilder (diffusion_graph.cpp defines them).
#pragma once

#include "sadr/common/particle_state.hpp"
#include "sadr/ssa/diffusion_graph.hpp"
#include "sadr/ssa/model.hpp"

namespace sadr::ssa::detail {

/// Dimension, finite positions inside walled axes, m, rho > 0, region indices < N.
void validate_particles(const Model& model, const ParticleState& p);
/// Sizes the arrays of g for p.size() vertices; fills volume, kind, is_wall.
void prepare_vertices(DiffusionGraph& g, const ParticleState& p);
/// The rows by a full-stencil cell search with explicit minimum image (boxes
/// with a periodic axis of fewer than 3 cells, where the single-image row search and the
/// candidate list cannot be used). Rows in cell order.
void build_rows_full_stencil(DiffusionGraph& g, const Model& model, const ParticleState& p);

}  // namespace sadr::ssa::detail
