// SPDX-License-Identifier: MIT
/// \file graph_diagnostics.hpp
/// Structure of the SSA diffusion graph a run will use (issue #18): connected
/// components, isolated voxels, degree statistics and the range of the edge
/// weights D_ij and of the jump rates kappa_s D_ij. Components are found with
/// Boost.Graph (connected_components on an undirected view of the CSR rows).
///
/// Definitions (docs/ssa-core.md "Graph diagnostics"):
///  * degree of voxel i: its out-edges, all targets (wall particles included);
///  * isolated: a non-wall voxel without an edge to another non-wall voxel: a
///    molecule there can only leave into a wall (or not at all), so it never
///    diffuses through the fluid;
///  * components: of the undirected graph on all voxels and all edges.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "sadr/ssa/diffusion_graph.hpp"
#include "sadr/ssa/model.hpp"

namespace sadr::ssa {

struct GraphDiagnostics {
  std::size_t voxels = 0;
  std::size_t wall_voxels = 0;
  std::size_t edges = 0;                          ///< directed (i -> j and j -> i counted apart)
  std::size_t components = 0;                     ///< connected components (all voxels, all edges)
  std::size_t largest_component = 0;              ///< voxels in the largest one
  std::size_t isolated = 0;                       ///< non-wall voxels with no non-wall neighbour
  std::optional<std::uint32_t> isolated_example;  ///< the first isolated voxel (particle index)
  std::size_t min_degree = 0;
  std::size_t max_degree = 0;
  double mean_degree = 0;
  double min_weight = 0;         ///< smallest D_ij over all edges [1/L^2] (0 without edges)
  double max_weight = 0;         ///< largest D_ij [1/L^2]
  double min_rate = 0;           ///< smallest kappa_s D_ij over diffusing species [1/T] (0 if none)
  double max_rate = 0;           ///< largest kappa_s D_ij [1/T]
  std::string min_rate_species;  ///< species of min_rate / max_rate ("" if none diffuses)
  std::string max_rate_species;

  /// Human-readable lines for the plan ("SSA graph: 400 voxels, ...").
  [[nodiscard]] std::vector<std::string> lines() const;
  /// A warning for isolated voxels ("" if there are none), naming the count and
  /// the example particle, for the plan and `sadr validate`.
  [[nodiscard]] std::string isolated_warning() const;
};

/// Diagnoses `graph`; the rates use the diffusivities of `model`'s species.
GraphDiagnostics diagnose_graph(const DiffusionGraph& graph, const Model& model);

}  // namespace sadr::ssa
