// SPDX-License-Identifier: MIT
/// \file backend_start.hpp
/// A backend's start, from the model and the initial state alone: initialised, the inflow
/// buffers imposed, and the sub-steps ahead from its stability limits at that state. The fluid
/// service's Init is this; so is the figure the plan prints before any service runs
/// (fluid::initial_substep_bound). No service and no messages here.
#pragma once

#include <span>
#include <vector>

#include "sadr/common/particle_state.hpp"
#include "sadr/fluid/fluid_backend.hpp"
#include "sadr/fluid/fluid_model.hpp"
#include "sadr/fluid/inflow.hpp"
#include "sadr/fluid/stability.hpp"

namespace sadr::fluid {

/// What a backend starts from: the model, the particles and the deterministic species'
/// concentrations ([species][particle], every species of the model, N values each).
struct BackendStart {
  FluidModel model;
  ParticleState particles;
  std::vector<std::vector<double>> concentrations;
  std::vector<InflowBuffer> inflows;
};

/// backend.initialize(model, particles, concentrations), then apply_inflows() (`scratch` and
/// `values` are its reusable buffers), then backend.current_substep_bound(). Throws what the
/// backend throws for a state it refuses.
SubstepBound start_backend(FluidBackend& backend, const BackendStart& start, ParticleState& scratch,
                           std::vector<double>& values);

}  // namespace sadr::fluid
