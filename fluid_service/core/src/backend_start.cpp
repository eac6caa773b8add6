// SPDX-License-Identifier: MIT
#include "sadr/fluid/backend_start.hpp"

namespace sadr::fluid {

SubstepBound start_backend(FluidBackend& backend, const BackendStart& start, ParticleState& scratch,
                           std::vector<double>& values) {
  backend.initialize(start.model, start.particles, start.concentrations);
  apply_inflows(backend, start.inflows, scratch, values);
  return backend.current_substep_bound();
}

}  // namespace sadr::fluid
