// SPDX-License-Identifier: MIT
/// \file diffusion_graph.hpp
/// The particle diffusion graph of docs/method.md section 4 (Tartakovsky / drawert2019
/// eq 28), in compressed-sparse-row form.
///
/// Representation: our own CSR arrays rather than
/// boost::compressed_sparse_row_graph. bench/ssa measures both on the same
/// edges (`ssa_bench boost_csr`): the NSM hot loop only needs "the out-edges
/// of voxel i with their weights, non-wall targets first", which a plain
/// row_start/col/weight triple gives with no indirection; Boost's CSR stores
/// edge properties in a separate bundled vector and has no notion of the
/// wall/non-wall split, and building it from the (already sorted) neighbour
/// rows costs extra passes. The measured figures are in docs/ssa-core.md.
#pragma once

#include <cstdint>
#include <vector>

#include "sadr/common/particle_state.hpp"
#include "sadr/ssa/huge_pages.hpp"
#include "sadr/ssa/model.hpp"

namespace sadr::ssa {

/// Lucy kernel radial factor F(r) = -(1/r) dW/dr >= 0 [1/L^(d+2)] for support radius h.
/// W(r) = alpha_d (1 + 3q)(1 - q)^3, q = r/h, so F = 12 alpha_d (1 - q)^2 / h^2 for q < 1.
double lucy_f(double r, double h, int dimension);

/// Per-edge weights D_ij (jump rate per molecule per unit diffusivity [1/L^2];
/// the rate of species s is kappa_s D_ij [1/T]).
class DiffusionGraph {
 public:
  /// Builds the graph of `particles` (cell lists, O(N)); validates the particles
  /// against the model (dimension, finite positions inside walled axes, m, rho > 0)
  /// and throws InvalidArgument naming field, particle index and value.
  static DiffusionGraph build(const Model& model, const ParticleState& particles);
  /// The same into an existing graph, reusing its allocations (the coupled run
  /// rebuilds every step). The particles are validated before `g` is touched,
  /// so on InvalidArgument `g` is unchanged.
  static void build_into(DiffusionGraph& g, const Model& model, const ParticleState& particles);

  [[nodiscard]] std::size_t size() const { return volume.size(); }
  [[nodiscard]] std::size_t edge_count() const { return edges.size(); }

  /// One directed edge; weight and target interleaved and packed to 12 bytes
  /// so that scanning a row during event selection touches as few cache lines
  /// as possible (6 lattice edges: 72 instead of 96 bytes; fewer simulated LL
  /// misses per event, docs/ssa-core.md).
#pragma pack(push, 4)
  struct Edge {
    double weight;         ///< D_ij [1/L^2] (directed: i -> j)
    std::uint32_t target;  ///< j
  };
#pragma pack(pop)
  static_assert(sizeof(Edge) == 12);

  // Row i: out-edges [row_start[i], row_start[i+1]); targets that are NOT wall
  // particles come first, in [row_start[i], split[i]).
  std::vector<std::uint32_t> row_start;  ///< N + 1
  std::vector<std::uint32_t> split;      ///< N
  /// Out-edges, row by row; on huge pages because the event loop reads the firing voxel's row
  /// at random (see huge_pages.hpp).
  std::vector<Edge, detail::HugePageAllocator<Edge>> edges;
  std::vector<double> sum_all;        ///< sum_j D_ij over all out-edges [1/L^2]
  std::vector<double> sum_nowall;     ///< sum_j D_ij over non-wall targets [1/L^2]
  std::vector<double> volume;         ///< V_i = m_i / rho_i [L^d]
  std::vector<std::uint8_t> is_wall;  ///< 1 for ParticleKind::kWall
  std::vector<ParticleKind> kind;     ///< particle kind
  std::vector<double>
      wall_distance;  ///< distance to the nearest wall particle within h, else +inf [L]
  int dimension = 3;
};

}  // namespace sadr::ssa
