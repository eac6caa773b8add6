// SPDX-License-Identifier: MIT
/// \file stability.hpp
/// Explicit time-step limits (docs/method.md section 5; Morris, Fox & Zhu 1997; Monaghan 1992).
/// The coefficients are Morris' for his smoothing length h_M; our h is the kernel SUPPORT
/// radius, and Morris' kernels have support 2 h_M, so h_M = h/2 below. Coefficients:
///  - acoustic   dt <= 0.25 h_M / (c0 + v_max)
///  - viscous    dt <= min(0.125 rho_min h_M^2 / eta, 1 / (eta max_i (a+b)/(eta rho_i) sum_j V_j
///  F_ij))
///               the second is the Gershgorin bound of the discrete viscous operator
///  - body force dt <= 0.25 sqrt(h_M / |a|_max)   (gravity + Boussinesq)
///  - diffusion  dt <= min(0.125 h_M^2 / kappa_max, 1 / max_i sum_j 2 kappa_max K_ij)
///               the second bound is the Gershgorin bound of the discrete operator
///               (Heun is stable for real eigenvalues in [-2/dt, 0]); it is the binding
///               one for wide kernels (h > ~2.5 dx).
///  - reaction   dt <= 1 / max_i |J_i|, with |J_i| the reaction Jacobian scale
///               (SpeciesTransport::reaction_rate_scale), margin 2 on Heun's limit.
#pragma once

#include <cstdint>
#include <limits>
#include <string>

namespace sadr::fluid {

struct StabilityLimits {
  static constexpr double kNone = std::numeric_limits<double>::infinity();
  double acoustic = kNone;    ///< [time]
  double viscous = kNone;     ///< [time]
  double body_force = kNone;  ///< [time]
  double diffusion = kNone;   ///< [time]
  double reaction = kNone;    ///< [time]

  /// The binding limit [time] and its name ("none" if all are infinite).
  [[nodiscard]] std::pair<double, std::string> smallest() const {
    std::pair<double, std::string> best{kNone, "none"};
    auto take = [&](double v, const char* n) {
      if (v < best.first) best = {v, n};
    };
    take(acoustic, "acoustic");
    take(viscous, "viscous");
    take(body_force, "body_force");
    take(diffusion, "diffusion");
    take(reaction, "reaction");
    return best;
  }
};

/// With force_time_step: warns (log::warn, once per limit name per process) when the forced
/// sub-step dt [time] breaks the binding limit, since such a run may give wrong but finite
/// results (bench/validation/stability_map.py); returns whether it warned.
bool warn_forced_substep(const StabilityLimits& limits, double dt);

/// Without force_time_step: warns (log::warn, once per limit name per process) when
/// max_time_step [time] is above the binding limit, which then sets the sub-step (the user's cap
/// does nothing there; the message names the limit and its value); returns whether it warned.
bool warn_unbinding_cap(const StabilityLimits& limits, double max_time_step);

/// The longest sub-step either rule below takes at `limits`, and what sets it.
struct SubstepBound {
  double limit = StabilityLimits::kNone;  ///< the binding stability limit [time] (inf: none)
  std::string limit_name = "none";        ///< its name (StabilityLimits::smallest())
  double dt = StabilityLimits::kNone;     ///< the longest sub-step [time] (inf: one per advance)
  std::string criterion = "none";         ///< what sets dt: limit_name or "max_time_step"
};
/// The binding limit, capped by `max_time_step` when that is > 0 and smaller; with `force`,
/// max_time_step itself. An advance of length T then takes ceil(T / dt) sub-steps. No warnings.
SubstepBound substep_bound(const StabilityLimits& limits, double max_time_step, bool force);

/// One sub-step chosen by next_substep().
struct Substep {
  double dt = 0.0;         ///< sub-step length [time]
  double limit = 0.0;      ///< the binding stability limit [time]
  std::string limit_name;  ///< its name ("acoustic", ...)
};

/// The two sub-step rules of the fluid core (docs/fluid-core.md, "Sub-steps"):
///  - adaptive (sdpd, static): next_substep() before every sub-step, from the limits at the
///    current state, so the sub-step count of an advance follows the flow;
///  - uniform (tdpd): uniform_substeps() once per advance, from the limits at its start,
///    `count` equal sub-steps (the velocity-Verlet pair forces carry over between them).

/// The next sub-step of what `remaining` [time] is left of an advance: `remaining` split
/// evenly into the fewest pieces no longer than the binding limit, or than `max_time_step`
/// when that is > 0 and smaller (an upper bound; with `force`, max_time_step itself, warned
/// through warn_forced_substep() when it breaks the limit). Lowers `stable_dt` and sets
/// `criterion` when the binding limit is tighter than what they hold (StepReport fields).
Substep next_substep(const StabilityLimits& limits, double max_time_step, bool force,
                     double remaining, double& stable_dt, std::string& criterion);

/// The uniform rule: the fewest equal sub-steps of `time_step` no longer than the binding limit,
/// or than min(limit, max_time_step) when max_time_step > 0 (`force` takes max_time_step as it
/// is and warns as next_substep() does).
struct UniformSubsteps {
  std::uint32_t count = 1;  ///< sub-steps
  double dt = 0.0;          ///< their length [time]
  double limit = 0.0;       ///< the binding stability limit [time]
  std::string limit_name;   ///< its name
};
UniformSubsteps uniform_substeps(const StabilityLimits& limits, double max_time_step, bool force,
                                 double time_step);

}  // namespace sadr::fluid
