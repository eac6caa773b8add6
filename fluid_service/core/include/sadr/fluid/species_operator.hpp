// SPDX-License-Identifier: MIT
/// \file species_operator.hpp
/// The SDPD species operator (eq-17 pair exchange + mass-action reactions, the wall conditions of
/// SpeciesTransport) on particles whose motion is not the operator's business: built on the
/// current positions, integrated with the trapezoidal predictor-corrector under the diffusion
/// and reaction limits. Used by "static" (built once) and "prescribed" (rebuilt after every
/// move). Bit-for-bit the loops the static backend always had.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "sadr/common/particle_state.hpp"
#include "sadr/fluid/fluid_backend.hpp"
#include "sadr/fluid/fluid_model.hpp"
#include "sadr/fluid/neighbor_list.hpp"
#include "sadr/fluid/species_transport.hpp"
#include "sadr/fluid/stability.hpp"

namespace sadr::fluid {

class SpeciesOperator {
 public:
  using Fields = std::vector<std::vector<double>>;
  /// Wall roles and reactions of `model` on `state`, then build(state).
  void setup(const FluidModel& model, const ParticleState& state);
  /// Neighbour list and pair coefficients at the positions of `state` (nothing to do without
  /// transported species).
  void build(const ParticleState& state);
  /// The integrator's scratch fields start as copies of c (call after set-up and Dirichlet).
  void reset_scratch(const Fields& c) {
    ctmp_ = c;
    dc0_ = c;
    dc1_ = c;
  }
  /// Whether any species is integrated here.
  [[nodiscard]] bool active() const { return !species_.transported().empty(); }
  [[nodiscard]] const SpeciesTransport& transport() const { return species_; }
  /// Diffusion and reaction limits at `c` [time].
  [[nodiscard]] StabilityLimits limits(const Fields& c, const ParticleState& state) const;
  /// dc = the rates at c (zeroed first).
  void rates(const ParticleState& state, const Fields& c, Fields& dc) const;
  /// Advances c by time_step in the adaptive sub-steps of next_substep() (limits at the start of
  /// each), adding each sub-step to `time`; `rep` gets stable_dt and the criterion; returns the
  /// sub-steps taken. A non-finite value throws NumericalFailure naming `backend`, step,
  /// sub-step, particle id and species.
  std::uint32_t advance(std::string_view backend, const ParticleState& state, Fields& c,
                        std::uint64_t step_index, double time_step, double& time, StepReport& rep);

 private:
  FluidModel model_;
  SpeciesTransport species_;
  NeighborList nlist_;
  std::vector<double> k_;    ///< DiffusionTerm coefficient per list entry [1/length^2]
  std::vector<double> xij_;  ///< minimum-image x_i - x_j per list entry (3 per entry)
  double max_k_sum_ = 0;
  Fields ctmp_, dc0_, dc1_;
};

}  // namespace sadr::fluid
