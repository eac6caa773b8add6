// SPDX-License-Identifier: MIT
/// \file fluid_backend.hpp
/// The seam between the fluid service and its numerical models (docs/fluid-core.md).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sadr/common/particle_state.hpp"
#include "sadr/fluid/backend_schema.hpp"
#include "sadr/fluid/fluid_model.hpp"
#include "sadr/fluid/stability.hpp"

namespace sadr::fluid {

/// Health and progress of one advance() call.
/// The force and torque the fluid exerted on one body over a step (FluidModel::body_forces).
struct BodyForce {
  std::string name;
  std::array<double, 3> force{};      ///< [mass length/time^2] (per unit length^(3-d))
  std::array<double, 3> torque{};     ///< about `reference` (2D: z only)
  std::array<double, 3> reference{};  ///< [length]
};

struct StepReport {
  double time = 0.0;               ///< model time after the call [time]
  std::uint32_t substeps = 0;      ///< sub-steps taken
  double max_speed = 0.0;          ///< max |v| over fluid particles [length/time]
  double min_density = 0.0;        ///< [mass/length^d]
  double max_density = 0.0;        ///< [mass/length^d]
  bool particles_moved = false;    ///< positions changed
  double stable_dt = 0.0;          ///< smallest stability limit seen [time] (inf if none)
  std::string limiting_criterion;  ///< "acoustic" | "viscous" | "body_force" | "diffusion" |
                                   ///< "reaction" | "none"
  /// FluidModel::body_forces in that order, averaged over the step (empty: none asked).
  std::vector<BodyForce> body_forces;
  /// min_density / max_density from the densities of every particle (left 0 if none).
  void set_density_band(std::span<const double> rho) {
    if (rho.empty()) return;
    const auto [lo, hi] = std::minmax_element(rho.begin(), rho.end());
    min_density = *lo;
    max_density = *hi;
  }
};

/// One fluid model. Input specification of the arrays:
///  - initial: ParticleState (layout in particle_state.hpp); wall particles have kind kWall.
///  - concentrations: [species][particle], species in FluidModel::species order; each inner
///    vector has N entries, or the outer vector is empty (all zero). Wall particles with a
///    Dirichlet condition are overwritten with the prescribed value.
class FluidBackend {
 public:
  virtual ~FluidBackend() = default;
  [[nodiscard]] virtual std::string_view name() const = 0;
  /// What this backend does: its entry in the backend schema (backend_schema.hpp), the one
  /// description that the scene loader, `sadr backends` and the tests read. Throws Internal if
  /// the backend has no entry (every backend of SADR_FLUID_BACKENDS has one).
  [[nodiscard]] const schema::Capabilities& capabilities() const;
  /// Validates everything (InvalidArgument naming field, value and range) and sets time = 0.
  virtual void initialize(const FluidModel& model, const ParticleState& initial,
                          const std::vector<std::vector<double>>& concentrations) = 0;
  /// Advances by time_step [time] in sub-steps respecting the stability limits.
  /// Same (seed, step_index) gives the same result on any thread count.
  /// Throws InvalidArgument (dt breaks a limit, not forced) or NumericalFailure (blow-up).
  virtual StepReport advance(std::uint64_t step_index, double time_step) = 0;
  virtual void read_state(ParticleState& out) const = 0;
  [[nodiscard]] virtual const std::vector<double>& concentrations(int species) const = 0;
  /// Overwrites species `species` (N values), e.g. back-transfer from the SSA.
  virtual void set_concentrations(int species, std::span<const double> values) = 0;
  /// Versioned binary blob of the full dynamic state (exact restart).
  [[nodiscard]] virtual std::string save() const = 0;
  /// Restores a blob from save() of the same backend initialised with the same model.
  virtual void restore(std::string_view blob) = 0;
  /// Model time [time].
  [[nodiscard]] virtual double time() const = 0;
  /// The sub-steps ahead from the current state, by the backend's own rule: its stability
  /// limits there (every criterion that rule applies, reactions included where it applies
  /// them) and the cap of max_time_step / force_time_step (substep_bound()). The fluid service
  /// reports it after initialize() (InitReply), for the plan. Leaves the trajectory as it is.
  [[nodiscard]] virtual SubstepBound current_substep_bound() = 0;
};

}  // namespace sadr::fluid
