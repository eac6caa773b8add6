// SPDX-License-Identifier: MIT
/// \file work_estimate.hpp
/// What a scene will cost before it runs: particles, memory per process (from
/// measured bytes per particle, bench/memory_per_particle.py), coupling steps
/// and fluid sub-steps (from the fluid backend's own limits at t = 0, which the
/// orchestrator does not re-derive), frames and output bytes, molecules and SSA events.
/// `sadr validate` and the plan print it; limits refuse a run that cannot
/// finish on this machine (hard: memory above the machine's, output above
/// the free disk, counts or steps beyond the exact integer range) or that
/// would take unreasonably long (soft: lifted by `sadr run --allow-large`).
#pragma once

#include <nlohmann/json.hpp>

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sadr/orchestrator/machine_limits.hpp"
#include "sadr/orchestrator/plan.hpp"
#include "sadr/orchestrator/scene.hpp"

namespace sadr::orchestrator {

/// What the fluid backend reports after init (sadr.fluid.v1.InitReply; FluidBackend::
/// current_substep_bound): its stability limits at t = 0 by its own rule, reactions included.
struct FluidSubsteps {
  double stable_time_step = 0;     ///< the binding stability limit [time] (inf: none)
  std::string limiting_criterion;  ///< its name ("acoustic" ... "reaction", "none")
  double max_substep = 0;          ///< the longest sub-step the backend takes [time] (inf: one)
  /// Whether a service reported it (one before these fields leaves zeros).
  [[nodiscard]] bool known() const { return max_substep > 0 && !limiting_criterion.empty(); }
  /// What sets max_substep: limiting_criterion, or "max_time_step" when the cap binds.
  [[nodiscard]] std::string criterion() const;
};

struct WorkEstimate {
  double particles = 0;
  double sadr_bytes = 0, fluid_bytes = 0, ssa_bytes = 0;  ///< peak RSS per process
  double coupling_steps = 0;
  bool step_control = false;  ///< time.tolerance: coupling_steps counts steps of the first length
  double substeps_per_step = 0;    ///< fluid sub-steps per coupling step (0: none or not known)
  double fluid_substeps = 0;       ///< fluid sub-steps in all, one realization (0: not known)
  std::string substep_limit;       ///< what sets them (FluidSubsteps::criterion(); "" not known)
  double stable_time_step = 0;     ///< the backend's binding stability limit at t = 0 [time]
  std::string limiting_criterion;  ///< its name
  bool substeps_unknown = false;   ///< the plan steps the fluid, but no backend figure was given
  /// > 0: the backend's t = 0 figure was not computed because initialising it in sadr would
  /// take about this many bytes (above half the machine's memory or the process limit)
  double substeps_skipped = 0;
  double frames = 0, output_bytes = 0;
  double molecules = 0;   ///< stochastic copy numbers at t = 0, all species
  double event_rate = 0;  ///< SSA events per unit time at t = 0 (diffusion + reactions)
  double events = 0;      ///< event_rate * end time
  /// Wall time of the whole request on a machine like the calibration's (2 cores) [s]: fluid
  /// sub-steps x particles x the backend's cost, graph rebuilds, SSA events, frames; 0 when the
  /// fluid's sub-steps are not known. The parts in `time_parts` ("fluid", "graph", "ssa",
  /// "frames").
  double wall_seconds = 0;
  std::vector<std::pair<std::string, double>> time_parts;
  /// Things to say before a run that are neither limits nor errors (a run longer than
  /// kLongRunSeconds).
  std::vector<std::string> notes;
  std::vector<std::string> hard;  ///< limits no option lifts, each with the figures
  std::vector<std::string> soft;  ///< limits lifted by --allow-large

  [[nodiscard]] double memory_bytes() const { return sadr_bytes + fluid_bytes + ssa_bytes; }
  [[nodiscard]] std::vector<std::string> lines() const;
  [[nodiscard]] nlohmann::json to_json() const;
};

/// The estimate of `scene` under `plan`, with the limits of `machine` checked,
/// for `realizations` runs of which `jobs` run at once (memory x jobs, the
/// rest x realizations). The fluid sub-steps per coupling step come from `fluid`, the
/// backend's report at t = 0 (without it they are not estimated, and said so).
WorkEstimate estimate_work(const Scene& scene, const Plan& plan, const MachineLimits& machine,
                           int realizations = 1, int jobs = 1,
                           const FluidSubsteps* fluid = nullptr);

/// Bytes sadr peaks at while it initialises the fluid backend in its own process for the
/// plan's t = 0 sub-step figure, before any run starts: one run's sadr figure plus
/// kInProcessInitFluidShare x its fluid figure (`estimate` counts `jobs` runs at once).
double in_process_init_bytes(const WorkEstimate& estimate, int jobs);
/// Whether that init may run: at most kSoftMemoryShare of the machine's memory and within the
/// per-process limit. Otherwise the plan gives no sub-step figure and says why.
bool in_process_init_fits(double bytes, const MachineLimits& machine);

/// Throws InvalidArgument with the estimate when a hard limit is exceeded, or
/// a soft one without `allow_large`.
void enforce_limits(const WorkEstimate& estimate, bool allow_large);

/// Soft thresholds (documented in docs/cli.md).
inline constexpr double kSoftMemoryShare = 0.5;  ///< of the machine's memory
/// sadr's peak while it initialises the fluid backend for the plan's t = 0 sub-step figure is
/// its own figure plus this share of the fluid service's: the Init message, the backend's start
/// decoded from it (the message is freed then) and the backend (measured 1.85x on the
/// ~1e5-particle sdpd coagulation channel: 248.5 MiB against sadr 61.9 + fluid 101 MiB
/// estimated; 2.0 with a margin).
inline constexpr double kInProcessInitFluidShare = 2.0;
inline constexpr double kSoftOutputBytes = 50e9;  ///< 50 GB of frames
inline constexpr double kSoftFrames = 1e5;
inline constexpr double kSoftCouplingSteps = 1e8;
inline constexpr double kSoftParticleSubsteps = 1e12;  ///< particles x fluid sub-steps
inline constexpr double kSoftEvents = 1e12;            ///< SSA events
/// Calibrated costs of the time estimate (bench/cost_calibration.py on the examples; the
/// fluid's per backend in its schema entry, CostPerParticle). Wall time on a 2-core machine.
inline constexpr double kSsaEventNs = 130;  ///< one SSA event (measured median 140 in 2D, 76 in 1D)
/// Rebuilding the particle diffusion graph, per particle and coupling step, in 1D, 2D, 3D
/// (measured 17 and 405; 3D not measured: 4x 2D's, for ~4x the neighbours).
inline constexpr std::array<double, 3> kGraphRebuildNs{20, 400, 1600};
inline constexpr double kFrameNsPerParticle = 2600;  ///< writing one particle of one frame
inline constexpr double kFrameSeconds = 2e-3;        ///< a frame's fixed cost (measured 1.6-2.4 ms)
/// A coupling step's fixed cost: the service calls and their messages [s].
inline constexpr double kStepSeconds = 4e-4;
/// A run whose estimated wall time is above this is announced before it starts [s].
inline constexpr double kLongRunSeconds = 3600;
/// Hard: step counters and copy numbers must stay exact integers in a double.
inline constexpr double kExactIntegerLimit = 9007199254740992.0;  // 2^53

}  // namespace sadr::orchestrator
