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
///
/// Speed: the search and the filter run row by row (each row its own full
/// stencil and its own sort), so both are split over OpenMP threads with the
/// same result for any thread count, and each has an AVX-512F path (runtime
/// dispatch, bit-identical to the scalar one: graph_filter.hpp, graph_search.hpp).
#pragma once

#include <cstdint>
#include <vector>

#include "sadr/common/particle_state.hpp"
#include "sadr/ssa/diffusion_graph.hpp"
#include "sadr/ssa/model.hpp"

namespace sadr::ssa {

namespace detail {
struct FilterParams;
struct FilterOutputs;
}  // namespace detail

class GraphBuilder {
 public:
  /// Skin as a fraction of h. 0.1: 34.2 candidates for 26.7 edges per particle in
  /// scenario d (2D, h = 3 dx), and with its motion (0.01 dx per axis per step) a search
  /// every ~8-10 steps (5 in 41 rebuilds). With 10x that motion every rebuild searches;
  /// the vectorised per-row search (graph_search.hpp) keeps that regime at about half
  /// the CPU time of the earlier pair-list search (bench/results/README-ssa.md).
  static constexpr double kSkinFraction = 0.1;

  /// Builds `g` from `particles` (validated first; on InvalidArgument `g` and the
  /// candidate list are unchanged). `force_search` ignores the candidate list.
  void build(DiffusionGraph& g, const Model& model, const ParticleState& particles,
             bool force_search = false);

  /// Threads for the row loops: 0 (default) = OpenMP's default (OMP_NUM_THREADS);
  /// the graph is the same for any count. Without OpenMP always 1.
  void set_threads(int threads) { threads_ = threads < 0 ? 0 : threads; }
  /// Threads a large rebuild uses (small ones run on one).
  [[nodiscard]] int threads() const;
  /// Use the AVX-512F search and filter when the CPU has it (default; the same
  /// candidate rows and graph bits as the scalar ones, which tests compare).
  void set_simd(bool on) { simd_ = on; }

  [[nodiscard]] std::uint64_t builds() const { return builds_; }      ///< build() calls
  [[nodiscard]] std::uint64_t searches() const { return searches_; }  ///< cell-list searches
  /// Directed candidate pairs in the current list.
  [[nodiscard]] std::size_t candidate_count() const {
    return cand_start_.empty() ? 0 : cand_start_.back();
  }

 private:
  /// Wraps the current positions into xw_; true if a new search is needed.
  bool wrap_and_check(const Model& model, const ParticleState& p, const DiffusionGraph& g);
  /// Candidate rows from a cell search at cutoff h (1 + skin); false if a periodic
  /// axis has < 3 cells (one cell reachable through two images: then the caller
  /// uses the explicit minimum-image full stencil).
  bool search(const Model& model, const ParticleState& p, const DiffusionGraph& g);
  /// The rows of g from the candidate list (rows in parallel ranges).
  void filter(DiffusionGraph& g, const Model& model, const ParticleState& p);
  /// Validation, vertices and wrap on the first of `nt` threads, then the filter on
  /// all of them, in one parallel region; false (nothing filtered) if a search is needed.
  bool prepare_and_filter(DiffusionGraph& g, const Model& model, const ParticleState& p, int nt);
  /// Filter inputs and outputs for g and p; sizes g.edges to the candidate bound.
  void filter_setup(DiffusionGraph& g, const Model& model, const ParticleState& p,
                    detail::FilterParams& prm, detail::FilterOutputs& o);
  /// One thread's share of the filter inside a parallel region (all threads call it).
  void filter_team(DiffusionGraph& g, const detail::FilterParams& prm,
                   const detail::FilterOutputs& o, std::vector<std::uint32_t>& counts);
  /// Total edge count from the per-range counts; trims g.edges.
  static void filter_finish(DiffusionGraph& g, std::size_t n,
                            const std::vector<std::uint32_t>& counts);
  /// Threads for a loop over `rows` rows (1 below kMinRowsPerThread per thread).
  [[nodiscard]] int thread_count(std::size_t rows) const;
  /// First row of range t of nt (ranges of about equal candidate counts).
  [[nodiscard]] std::size_t row_split(int t, int nt) const;

  static constexpr std::size_t kMinRowsPerThread = 1024;
  /// Thread ranges the parallel filter supports (threads() beyond this are not used).
  static constexpr int kMaxCopyRanges = 64;

  std::vector<double> xw_;    ///< current coordinates, wrapped, D per particle
  std::vector<double> xref_;  ///< the same at the last search
  std::vector<std::uint8_t> wall_ref_;
  std::vector<std::uint32_t> cand_start_;  ///< N + 1
  std::vector<std::uint32_t> cand_split_;  ///< first wall target in row i
  std::vector<std::uint32_t> cand_;        ///< candidate targets, rows as above, + kCandSlack zeros
  std::vector<std::vector<DiffusionGraph::Edge>> edge_scratch_;  ///< per thread > 0
  std::vector<std::vector<std::uint32_t>> cand_scratch_;         ///< per thread
  std::vector<std::uint32_t> wall_cell_;  ///< wall flags in cell order (search scratch)
  int threads_ = 0;
  bool simd_ = true;
  bool valid_ = false;
  std::uint64_t builds_ = 0, searches_ = 0;
};

}  // namespace sadr::ssa
