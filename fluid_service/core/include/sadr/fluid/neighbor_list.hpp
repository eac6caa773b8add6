// SPDX-License-Identifier: MIT
/// \file neighbor_list.hpp
/// Full (both-direction) neighbour lists built with a cell list, plus the O(N^2)
/// brute-force reference used by the tests (Cabana style).
///
/// Layout (CSR): the neighbours of particle i are indices[offsets[i] .. offsets[i+1]),
/// sorted by index, i itself excluded. A pair (i, j) is listed iff |x_i - x_j| < cutoff
/// with the minimum-image convention on periodic axes. Sorting makes the summation order
/// of every pair loop independent of when (and on how many threads) the list was built,
/// which is what makes save/restore and thread-count independence bit-exact.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "sadr/common/particle_state.hpp"
#include "sadr/fluid/periodic_box.hpp"

namespace sadr::fluid {

struct NeighborList {
  std::vector<std::uint32_t> offsets;  ///< N + 1 entries
  std::vector<std::uint32_t> indices;  ///< neighbour indices, sorted within each particle
  [[nodiscard]] std::size_t size() const { return offsets.empty() ? 0 : offsets.size() - 1; }
  [[nodiscard]] std::span<const std::uint32_t> of(std::size_t i) const {
    return {indices.data() + offsets[i], indices.data() + offsets[i + 1]};
  }
};

/// Cell-list builder for one box and cutoff.
class CellListBuilder {
 public:
  /// @param box domain (periodic axes need length >= 2 cutoff, else InvalidArgument).
  /// @param cutoff list radius [length] (> 0).
  CellListBuilder(const Box& box, double cutoff);
  /// Builds the full lists for positions (3N doubles, ParticleState layout).
  /// Particles outside the box on a walled axis are binned into the edge cells.
  void build(std::span<const double> positions, NeighborList& out) const;
  [[nodiscard]] double cutoff() const { return cutoff_; }

 private:
  /// Cells of width >= cutoff/2 and a 5^D stencil: 5^3/8 = 15.6 cutoff^3 of candidates per
  /// particle instead of 27 cutoff^3 with cutoff-wide cells (3D), 6.25 instead of 9 (2D).
  static constexpr int kCellReach = 2;
  /// Expected list entries for n uniformly spread particles (n x density x cutoff ball, at most
  /// n^2): the buffers' reservation, so they seldom grow by doubling.
  [[nodiscard]] std::size_t expected_entries(std::size_t n) const;
  PeriodicBox pbox_;
  double cutoff_;
  std::array<int, 3> ncell_{1, 1, 1};
  std::array<double, 3> inv_cell_{1, 1, 1};
};

/// O(N^2) reference with the same contract as CellListBuilder::build.
NeighborList brute_force_neighbors(const Box& box, double cutoff,
                                   std::span<const double> positions);

}  // namespace sadr::fluid
