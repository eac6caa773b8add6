// SPDX-License-Identifier: MIT
/// \file graph_filter.hpp
/// The per-row part of GraphBuilder's rebuild: candidate rows -> edges with r < h
/// and their weights D_ij (docs/method.md section 4), plus the per-row candidate search.
/// Rows are independent, so GraphBuilder runs these on row ranges in parallel;
/// the results do not depend on how the rows are split.
///
/// Two implementations of filter_rows() with the same arithmetic per edge (same
/// operations in the same order, no FMA contraction: graph_filter.cpp is built
/// with -ffp-contract=off; sqrt and division are correctly rounded in both): a
/// scalar one and an AVX-512F one (8 candidates per step: loads, minimum
/// image, r^2 < h^2, weights, register compress of the survivors). The AVX-512F
/// one runs when the CPU has it; tests check both give the same bits.
///
/// Row sums: the weights of a row part (non-wall, then wall targets) are summed in
/// 8 lanes, edge q of the part into lane q % 8 (by edge, not by candidate: the
/// candidates depend on the last search, the edges do not), and the lanes reduced as
/// ((s0 + s4) + (s2 + s6)) + ((s1 + s5) + (s3 + s7)) (sum8_lanes()). Both paths do
/// exactly this, so the sums agree bit for bit; the SIMD path keeps the lanes in one
/// register (a serial sum was a 32-cycle dependency chain per 8 candidates).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "sadr/ssa/diffusion_graph.hpp"

namespace sadr::ssa::detail {

/// Inputs of filter_rows(), all read-only.
struct FilterParams {
  int dim = 3;
  const double* x = nullptr;  ///< wrapped coordinates, dim per particle
  /// Minimum image per axis: len 0 and half +inf on walled axes (identity there).
  double len[3] = {0, 0, 0}, half[3] = {0, 0, 0};
  double h2 = 0, eps_h2 = 0, inv_h = 0, f0 = 0;  ///< h^2, eps h^2, 1/h, F(0)
  bool symmetric = false;                        ///< JumpConvention::kSymmetric
  const double* m = nullptr;
  const double* rho = nullptr;
  const double* vol = nullptr;
  const std::uint32_t* cand_start = nullptr;  ///< N + 1
  const std::uint32_t* cand_split = nullptr;  ///< first wall candidate of each row
  /// Rows: non-wall targets, then wall targets; followed by kCandSlack valid particle
  /// indices (the SIMD path loads 8 targets at a time and masks off those past the row).
  const std::uint32_t* cand = nullptr;
};

/// Valid particle indices the candidate array holds past its last row (see FilterParams::cand).
inline constexpr std::size_t kCandSlack = 8;

/// Per-row outputs of filter_rows() (arrays indexed by particle).
struct FilterOutputs {
  std::uint32_t* row_start = nullptr;
  std::uint32_t* split = nullptr;
  double* sum_nowall = nullptr;
  double* sum_all = nullptr;
  double* wall_distance = nullptr;
};

/// Edges filter_rows() may write past its returned count (the SIMD path stores
/// 8 edges at a time); the edge buffer needs this much room beyond the candidates.
inline constexpr std::size_t kFilterSlack = 8;

/// True if the AVX-512F filter runs on this CPU (and the build has it).
bool filter_simd_available();

/// Filters the candidate rows [i0, i1): writes their edges to e[0..count), the
/// row offsets (relative to e) to row_start/split, and the sums and wall
/// distances; returns count. `e` needs room for the rows' candidates plus
/// kFilterSlack. `simd`: use the AVX-512F path if available (same bits).
std::uint32_t filter_rows(const FilterParams& p, std::size_t i0, std::size_t i1,
                          DiffusionGraph::Edge* e, const FilterOutputs& o, bool simd = true);

}  // namespace sadr::ssa::detail
