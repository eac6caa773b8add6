// SPDX-License-Identifier: MIT
/// \file static_backend.hpp
/// "static": the particles never move; densities, masses and positions stay those of the
/// initial state. Costs nothing per step when there are no deterministic species. When
/// there are, it integrates them on the frozen particles with exactly the SDPD species
/// operator (docs/method.md eq (17) + mass-action reactions, trapezoidal predictor-corrector, the
/// same wall conditions), so frozen-particle diffusion references (tests/fluid/validation) can be
/// run without a flow.
#pragma once

#include "sadr/fluid/backend_base.hpp"
#include "sadr/fluid/backend_registry.hpp"
#include "sadr/fluid/species_operator.hpp"

namespace sadr::fluid {

class StaticBackend final : public BackendBase {
 public:
  [[nodiscard]] std::string_view name() const override { return "static"; }
  [[nodiscard]] double time() const override { return time_; }
  /// Stability limits at the current concentrations.
  [[nodiscard]] StabilityLimits current_limits() const;
  /// current_limits() (diffusion, reaction) under max_time_step / force_time_step; no limit
  /// without transported species (one sub-step per advance).
  [[nodiscard]] SubstepBound current_substep_bound() override {
    if (!species_.active()) return {};
    return substep_bound(current_limits(), model_.max_time_step, model_.force_time_step);
  }

 protected:
  void setup(const FluidModel& model, const ParticleState& initial,
             const std::vector<std::vector<double>>& concentrations) override;
  StepReport step(std::uint64_t step_index, double time_step) override;
  void write_state(ParticleState& out) const override { out = state_; }
  std::vector<std::vector<double>>& fields() override { return c_; }
  const std::vector<std::vector<double>>& fields() const override { return c_; }
  const SpeciesTransport& transport() const override { return species_.transport(); }
  std::uint32_t state_version() const override { return 1; }
  void save_state(BlobWriter& w) const override;
  void restore_state(BlobReader& r, std::uint32_t version) override;

 private:
  FluidModel model_;
  ParticleState state_;
  std::vector<std::vector<double>> c_;
  SpeciesOperator species_;  ///< built once: the particles never move
  double time_ = 0;
};

/// Registers "static" (called by the generated register_builtin_backends(), backends.cmake).
void register_static_backend(BackendRegistry& registry);

}  // namespace sadr::fluid
