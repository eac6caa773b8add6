// SPDX-License-Identifier: MIT
/// \file plan.hpp
/// What a run needs, decided from the scene alone (printed at start and
/// stored in the run manifest). Skip rules:
///  - no ssa_service without stochastic species;
///  - no fluid stepping for a backend that moves no particles (its schema entry; the SSA
///    graph is built once);
///    no fluid_service at all when it also has no deterministic species;
///  - no thermal noise at k_B T = 0 (no random numbers drawn by the fluid);
///  - no back-transfer of copy numbers to the fluid unless a fluid term depends
///    on a stochastic species (Boussinesq);
///  - no coupling step when nothing moves and only the SSA runs (static backend,
///    no fluid_service, no stochastic inflow buffer to reset): the SSA advances
///    from output time to output time (and checkpoint and stop times) in one
///    call each, with the same results (the NSM's pending event times carry over
///    from one call to the next);
///  - only the species each service needs go on the wire;
///  - no fluid in all but one pass of an ensemble when the fluid does not depend
///    on the realization (flow replay: no thermal noise, no back-transfer): the
///    fluid is computed once and its coupling data replayed to every realization.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "sadr/orchestrator/scene.hpp"

namespace sadr::orchestrator {

struct Plan {
  std::string fluid_backend;  ///< backend name from the scene (sdpd, static, tdpd)
  bool fluid_service = true;  ///< launch fluid_service
  bool fluid_stepping =
      true;  ///< advance the fluid every coupling step (particles move, or deterministic species)
  bool ssa_service = false;                 ///< launch ssa_service
  bool graph_rebuild_each_step = false;     ///< particles move: the SSA graph is rebuilt every step
  bool particles_to_ssa_each_step = false;  ///< positions/densities/masses fluid -> ssa per step
  bool thermal_noise = false;  ///< the fluid draws thermal noise (k_B T > 0, moving backend)
  bool back_transfer = false;  ///< copy numbers ssa -> fluid before every fluid step
  Splitting splitting = Splitting::kLie;
  int fluid_calls_per_step = 0;  ///< 0, 1 (Lie) or 2 (Strang half steps)
  /// Skip the coupling step: SSA alone, nothing moves, nothing reset between
  /// calls; steps go frame to frame (splitting.hpp FrameToFrame).
  bool frame_to_frame = false;
  /// time.tolerance with both operators: the coupling step is error-controlled
  /// (docs/method.md section 1b); `tolerance` is the scene's.
  bool step_control = false;
  StepTolerance tolerance;
  double first_step = 0.0;                         ///< time.coupling_step [time]
  std::vector<std::string> fluid_species;          ///< on the fluid wire (deterministic + fed back)
  std::vector<std::string> ssa_species;            ///< on the SSA wire (stochastic)
  std::vector<std::string> back_transfer_species;  ///< stochastic species the fluid reads
  /// Hybrid reactions: deterministic species the SSA's laws read, sent fluid -> ssa with
  /// every SSA stage and held frozen over it (docs/method.md section 4c).
  std::vector<std::string> frozen_species;
  bool ssa_time_laws = false;  ///< an SSA law reads t (held at each stage's start)
  /// `ssa.method: adaptive`: its tolerance (docs/method.md "Adaptive SSA"); 0 = exact NSM.
  double ssa_adaptive_tolerance = 0;
  std::size_t fluid_reactions = 0;   ///< reactions among deterministic species
  std::size_t ssa_reactions = 0;     ///< reactions among stochastic species
  std::vector<std::string> skipped;  ///< one line per skipped piece, with the reason
  std::vector<std::string> chosen;   ///< settings chosen for keys left out (Scene::chosen)
  /// The scene allows running the SSA stage of step k at the same time as the
  /// fluid stage of step k + 1: Lie splitting, both services, fluid stepping,
  /// no back-transfer (the fluid never reads the SSA, so results are identical).
  bool overlap_allowed = false;
  /// Overlap is on for this run (decide_overlap(): allowed, and requested or a
  /// spare core); `overlap_reason` says why it is on or off.
  bool overlap = false;
  std::string overlap_reason;
  /// The fluid is the same in every realization (it draws no random numbers and
  /// reads nothing of the SSA), so an ensemble may compute it once and replay it.
  bool flow_replay_allowed = false;
  /// Flow replay is on for this run (decide_flow_replay()); `flow_replay_reason`
  /// says why it is on or off.
  bool flow_replay = false;
  std::string flow_replay_reason;

  /// Human-readable lines ("fluid_service: sdpd, stepping every coupling step", ...).
  [[nodiscard]] std::vector<std::string> lines() const;
  [[nodiscard]] nlohmann::json to_json() const;
};

/// The plan of `scene` (a pure function of it; overlap stays off until decide_overlap()).
Plan make_plan(const Scene& scene);

/// --overlap / --no-overlap / neither (auto).
enum class OverlapRequest { kAuto, kOn, kOff };

/// Sets plan.overlap and plan.overlap_reason. Auto: on when the scene allows it
/// and each realization has at least two hardware threads
/// (hardware_threads / jobs >= 2), even when the fluid's OpenMP team uses them
/// all: on the 2-core machine, fluid 2 threads + SSA overlapped was 6-8 % faster
/// (median wall time per step) than sequential, and 9-17 % with one fluid and
/// one SSA thread (bench/results/README-coupled.md "Overlap"). One hardware
/// thread per realization (e.g. -r 2 -j 2 on 2 cores): off.
/// @param fluid_threads OpenMP threads of the fluid (--fluid-threads, else
///        OMP_NUM_THREADS, else hardware_threads); reported in the reason
/// @param jobs realizations run at once
void decide_overlap(Plan& plan, OverlapRequest request, unsigned hardware_threads,
                    int fluid_threads, int jobs);

/// Sets plan.flow_replay and plan.flow_replay_reason: on when the scene allows it
/// (flow_replay_allowed), `refused` (--no-flow-replay) is false and the run has
/// at least two realizations.
void decide_flow_replay(Plan& plan, bool refused, int realizations);

}  // namespace sadr::orchestrator
