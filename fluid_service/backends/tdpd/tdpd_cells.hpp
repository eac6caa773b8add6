// SPDX-License-Identifier: MIT
/// \file tdpd_cells.hpp
/// The half ("forward") Verlet list of the tDPD pair loop, built directly with a cell list whose
/// layers along the last active axis are the slabs of the core SlabScheduler (slab_scheduler.hpp):
/// cells are at least cutoff / 2 wide, so a pair within the cutoff lies at most 2 cells apart on
/// every axis. Particle i lists j if |x_i - x_j| < cutoff (minimum image) and j lies 1 or 2 layers
/// ahead (mod the layer count on a periodic axis), or in the same layer with j > i: every pair
/// once, and a pair spans at most 3 consecutive slabs. Only the 75 cells of the forward half of the
/// 5 x 5 x 5 block are visited and nothing is sorted (the core CellListBuilder visits 27 cells
/// of width >= cutoff twice and sorts each list: ~3x the candidates). Each particle's list is
/// in a fixed order (cells, then index), so the list is a pure function of the positions and
/// independent of the thread count.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "sadr/fluid/neighbor_list.hpp"
#include "sadr/fluid/periodic_box.hpp"
#include "sadr/fluid/slab_scheduler.hpp"

namespace sadr::fluid::tdpd {

struct HalfList {
  NeighborList list;  ///< forward pairs of every particle (CSR)
  /// The layers along the last active axis as slabs of the core SlabScheduler (members in cell
  /// order within a layer); the backend hands them to its scheduler (SlabScheduler::set).
  SlabPartition slabs;
  std::size_t max_len = 0;  ///< longest forward list
};

/// Builds the half list of `positions` (3N, wrapped into the box on periodic axes; outside a
/// walled axis they are binned into the edge cells). Periodic axes need length >= 2 cutoff.
void build_half_list(const PeriodicBox& box, double cutoff, std::span<const double> positions,
                     HalfList& out);

}  // namespace sadr::fluid::tdpd
