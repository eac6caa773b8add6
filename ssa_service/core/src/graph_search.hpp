// SPDX-License-Identifier: MIT
/// \file graph_search.hpp
/// The candidate search of GraphBuilder, one row at a time: row i lists every
/// j != i closer than the grid's cutoff, non-wall targets ascending, then wall
/// targets ascending. Rows are independent (each scans its own 3^d cells), so
/// GraphBuilder runs row ranges on threads; sorted rows make the list
/// independent of the cell order, the history and the split into ranges.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "cell_grid.hpp"

namespace sadr::ssa::detail {

/// Appends the candidate rows [r0, r1) to `out` (its old content is dropped) and
/// their lengths to deg_nw[i] (non-wall targets) and deg_w[i] (wall targets).
/// `wall` is indexed by particle, `wall_cell` (0 or 1) in the grid's cell order.
/// Requires grid.single_image() (no per-pair minimum image). `simd`: the
/// AVX-512F scan and sort if the CPU has it (the same rows).
void search_rows(const CellGrid& grid, const std::uint8_t* wall, const std::uint32_t* wall_cell,
                 std::size_t r0, std::size_t r1, std::vector<std::uint32_t>& out,
                 std::uint32_t* deg_nw, std::uint32_t* deg_w, bool simd = true);

}  // namespace sadr::ssa::detail
