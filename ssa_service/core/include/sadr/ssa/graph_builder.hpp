// SPDX-License-Identifier: MIT
/// \file graph_builder.hpp
/// Rebuilds the DiffusionGraph at every coupling step without a neighbour
/// search at every step: a Verlet candidate list with a skin.
///
/// The candidate list holds every pair closer than h (1 + kSkinFraction) at the
/// positions of the last search (the reference). While every particle stays
/// within skin/2 of its reference position (minimum image), every pair closer
/// than h now is a candidate, so a rebuild only recomputes distance and weight
/// of the stored candidates. A search is redone when some particle moved
/// further, when the wall flags or N change, or on the first call.
///
/// The result does not depend on the history: candidate rows are sorted
/// (non-wall targets ascending, then wall targets ascending) and filtered with
/// r_ij < h and positive weights, so the graph is exactly the graph a fresh
/// search gives (same edges in the same order, same weights bit for bit;
/// DiffusionGraph::build_into() runs the same code with a forced search). A
/// restored snapshot therefore rebuilds the same graph. Tested against brute
/// force with moving particles (diffusion_graph_test.cpp, GraphBuilder.*).
#pragma once

#include <cstdint>
#include <vector>

#include "sadr/common/particle_state.hpp"
#include "sadr/ssa/diffusion_graph.hpp"
#include "sadr/ssa/model.hpp"

namespace sadr::ssa {

class GraphBuilder {
 public:
  /// Skin as a fraction of h. 0.1: 34.2 candidates for 26.7 edges per particle in
  /// scenario d (2D, h = 3 dx), and with its motion (0.01 dx per axis per step) a search
  /// every ~8-10 steps (5 in 41 rebuilds). With 10x that motion every rebuild searches
  /// and the rebuild is ~1.5x the old fused search (bench/results/README-ssa.md); a skin
  /// of ~0 measured 500-597 vs 594-748 ns/voxel there, still above the old 340-430.
  static constexpr double kSkinFraction = 0.1;

  /// Builds `g` from `particles` (validated first; on InvalidArgument `g` and the
  /// candidate list are unchanged). `force_search` ignores the candidate list.
  void build(DiffusionGraph& g, const Model& model, const ParticleState& particles,
             bool force_search = false);

  [[nodiscard]] std::uint64_t builds() const { return builds_; }      ///< build() calls
  [[nodiscard]] std::uint64_t searches() const { return searches_; }  ///< cell-list searches
  /// Directed candidate pairs in the current list.
  [[nodiscard]] std::size_t candidate_count() const { return cand_.size(); }

 private:
  /// Wraps the current positions into xw_; true if a new search is needed.
  bool wrap_and_check(const Model& model, const ParticleState& p, const DiffusionGraph& g);
  /// Candidate rows from a cell search at cutoff h (1 + skin); false if the box
  /// is too small for the half stencil (then the caller uses the full stencil).
  bool search(const Model& model, const ParticleState& p, const DiffusionGraph& g);
  template <int D>
  void filter(DiffusionGraph& g, const Model& model, const ParticleState& p) const;

  std::vector<double> xw_;    ///< current coordinates, wrapped, D per particle
  std::vector<double> xref_;  ///< the same at the last search
  std::vector<std::uint8_t> wall_ref_;
  std::vector<std::uint32_t> cand_start_;  ///< N + 1
  std::vector<std::uint32_t> cand_split_;  ///< first wall target in row i
  std::vector<std::uint32_t> cand_;        ///< candidate targets, rows as above
  bool valid_ = false;
  std::uint64_t builds_ = 0, searches_ = 0;
};

}  // namespace sadr::ssa
