// SPDX-License-Identifier: MIT
/// \file inflow.hpp
/// Inflow buffers (sadr::InflowBox, common/inflow_box.hpp): boxes in which the copy number
/// of a species is re-imposed as round(c V_i) on the particles currently
/// inside, at Init and at the start of every Advance. With a periodic flow
/// this turns a slab into an inlet at a fixed concentration, and particles
/// that re-enter it through the periodic boundary drop what they carried
/// (the outlet). Between two resets the buffer particles exchange molecules
/// with their neighbours like any voxel (documented in docs/scene-format.md).
#pragma once

#include <span>
#include <string>
#include <vector>

#include "sadr/common/inflow_box.hpp"
#include "sadr/common/particle_state.hpp"

namespace sadr::ssa {

class NsmSolver;

struct InflowBuffer {
  int species = 0;  ///< index among the stochastic species
  InflowBox box;    ///< where and which concentration
};

/// Re-imposes every buffer on the particles the solver's graph was built from.
/// @return true if some count changed (the solver's queue was rebuilt).
bool apply_inflows(NsmSolver& solver, std::span<const InflowBuffer> inflows);

}  // namespace sadr::ssa
