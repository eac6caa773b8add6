// SPDX-License-Identifier: MIT
/// \file neighbor_list.hpp
/// All particle pairs closer than a cutoff, by cell lists in O(N) (and by brute
/// force in O(N^2) for tests). Periodic axes use the minimum image; walled axes
/// do not wrap.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "sadr/common/particle_state.hpp"

namespace sadr::ssa {

/// Full (both directions) neighbour list in compressed-row form.
/// Row i holds the neighbours j != i with |x_i - x_j| < cutoff in
/// [row_start[i], row_start[i+1]); r2[k] is the squared distance [L^2].
struct NeighborList {
  std::vector<std::uint32_t> row_start;  ///< N + 1 offsets
  std::vector<std::uint32_t> col;        ///< neighbour indices
  std::vector<double> r2;                ///< squared pair distances [L^2]
  [[nodiscard]] std::size_t size() const { return row_start.empty() ? 0 : row_start.size() - 1; }
};

/// Cell-list neighbour search, O(N) for bounded density.
/// @param box       domain (dimension d, periodic flags; cutoff < L/2 on periodic axes)
/// @param positions 3N coordinates, particle i at [3i, 3i+3) [L]; axes >= d are ignored
/// @param cutoff    search radius [L], > 0; pairs with r < cutoff are kept
/// Rows list neighbours in a deterministic (cell) order.
NeighborList build_neighbor_list(const Box& box, std::span<const double> positions, double cutoff);

/// O(N^2) reference with the same semantics; rows sorted by neighbour index.
NeighborList brute_force_neighbor_list(const Box& box, std::span<const double> positions,
                                       double cutoff);

}  // namespace sadr::ssa
