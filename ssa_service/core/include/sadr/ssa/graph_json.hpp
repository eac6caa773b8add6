// SPDX-License-Identifier: MIT
/// \file graph_json.hpp
/// Dumps the jump rates of a diffusion graph as the explicit-graph JSON that
/// tests/ssa/linear_rdme_reference.py reads ("n_voxels", "edges": [[i, j, d_ij]],
/// plus the first-order network and output times), so the exact mean and
/// variance of a first-order RDME can be computed for OUR rates.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "sadr/ssa/diffusion_graph.hpp"

namespace sadr::ssa {

/// The first-order network that goes with the graph in the JSON.
struct LinearRdmeSpec {
  double kappa = 1;                        ///< diffusivity [L^2/T]: d_ij = kappa D_ij
  double decay = 0;                        ///< "k": A -> 0 per molecule [1/T]
  std::vector<double> birth;               ///< "b": 0 -> A per voxel [1/T] (1 or N values)
  std::vector<std::int64_t> x0;            ///< initial counts (N values)
  std::vector<std::uint32_t> fixed_index;  ///< reservoir voxels
  std::vector<std::int64_t> fixed_count;   ///< their counts
  std::vector<double> times;               ///< output times [T]
  bool variance = true;
  bool include_wall_edges = true;  ///< false: drop edges to/from wall particles (no-flux)
};

/// JSON text (doubles printed with 17 significant digits).
std::string graph_to_json(const DiffusionGraph& graph, const LinearRdmeSpec& spec);

}  // namespace sadr::ssa
