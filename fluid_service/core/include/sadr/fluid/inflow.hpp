// SPDX-License-Identifier: MIT
/// \file inflow.hpp
/// Inflow buffers of deterministic species (sadr::InflowBox,
/// common/inflow_box.hpp): after Init and after every advance, the
/// concentration of the particles inside a box is set to the box's value,
/// whatever the backend (the SSA does the same with copy numbers:
/// ssa_service/core/.../inflow.hpp).
#pragma once

#include <span>
#include <vector>

#include "sadr/common/inflow_box.hpp"
#include "sadr/common/particle_state.hpp"
#include "sadr/fluid/fluid_backend.hpp"

namespace sadr::fluid {

struct InflowBuffer {
  int species = 0;  ///< deterministic species index (FluidModel::species order)
  InflowBox box;
};

/// Re-imposes every buffer on the backend's current particles. `state` and
/// `values` are scratch buffers, reused between calls (no allocation per step).
inline void apply_inflows(FluidBackend& backend, std::span<const InflowBuffer> inflows,
                          ParticleState& state, std::vector<double>& values) {
  if (inflows.empty()) return;
  backend.read_state(state);
  for (const InflowBuffer& in : inflows) {
    values = backend.concentrations(in.species);
    bool changed = false;
    for (std::size_t i = 0; i < state.size(); ++i) {
      if (values[i] != in.box.concentration && in.box.contains(&state.positions[3 * i])) {
        values[i] = in.box.concentration;
        changed = true;
      }
    }
    if (changed) backend.set_concentrations(in.species, values);
  }
}

}  // namespace sadr::fluid
