// SPDX-License-Identifier: MIT
/// \file splitting_loop.hpp
/// The Lie/Strang coupling loop (docs/method.md section 1) over
/// the service interfaces: steps shortened to land on output times and the
/// end (next_coupling_step), the geometry handed from each fluid stage to the
/// SSA stage after it, the back-transfer of copy numbers, and the overlap of
/// SSA step k with fluid step k + 1. Frames and checkpoints are the caller's,
/// through hooks, called when both services are idle.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sadr/orchestrator/plan.hpp"
#include "sadr/orchestrator/run_manifest.hpp"
#include "sadr/orchestrator/scene.hpp"
#include "sadr/orchestrator/service_interfaces.hpp"
#include "sadr/orchestrator/splitting.hpp"
#include "sadr/orchestrator/step_control.hpp"

namespace sadr::orchestrator {

struct LoopSettings {
  Splitting splitting = Splitting::kLie;
  double tau = 0.0;                  ///< coupling step [time]
  double t_end = 0.0;                ///< [time]
  std::vector<double> output_times;  ///< sorted [time]
  double checkpoint_every = 0.0;     ///< simulated time between checkpoints; <= 0: none
  /// Checkpoint and stop after the first step that reaches this time [time].
  double stop_at = std::numeric_limits<double>::infinity();
  bool fluid_stepping = true;       ///< the fluid is advanced (not static)
  int fluid_calls_per_step = 1;     ///< fluid calls per coupling step (step index stride)
  bool geometry_each_step = false;  ///< particles move: geometry fluid -> ssa per SSA stage
  /// Stochastic species the fluid reads: copy numbers go to the fluid before
  /// every fluid stage (empty: no back-transfer).
  std::vector<std::string> back_transfer;
  /// Deterministic species the SSA's hybrid laws read: the fluid stage before each
  /// SSA stage returns them, the SSA holds them frozen over the stage (empty: none).
  std::vector<std::string> frozen;
  /// Skip the coupling step (Plan::frame_to_frame: SSA alone, nothing moves):
  /// steps go from output to output, checkpoint and stop time (FrameToFrame).
  bool frame_to_frame = false;
  /// Overlap SSA step k with fluid step k + 1 (used only where results cannot
  /// change: Lie, both services, fluid stepping, no back-transfer).
  bool overlap = false;
  /// time.tolerance with both operators running (Plan::step_control): each step's
  /// splitting error is estimated, the step accepted or redone (StepController).
  std::optional<StepTolerance> tolerance;
  /// Largest squared change of a fed-back copy number in one SSA event (noise bound).
  double jump2 = 1.0;
};

/// The loop settings of `scene` run as `plan` (stop_at: none).
LoopSettings make_loop_settings(const Scene& scene, const Plan& plan);

struct LoopHooks {
  /// A step ended on output time `t` (index into output_times).
  std::function<void(std::size_t index, double t)> frame;
  /// Write a checkpoint of the current state.
  std::function<void()> checkpoint;
  /// A stop was requested (signal): checkpoint and stop after this step.
  std::function<bool()> stop_requested;
  /// After every step (progress display).
  std::function<void(double t, std::uint64_t steps)> progress;
  /// After every coupling step, per fluid stage that reported forces on bodies: the stage's
  /// end time t, its length dt and the forces (averaged over the stage).
  std::function<void(double t, double dt, const std::vector<BodyForceSample>&)> body_forces;
};

class SplittingLoop {
 public:
  /// `fluid` / `ssa` may be null when the plan runs without that service;
  /// they must outlive the loop. Timings and counters go to `stats`.
  SplittingLoop(FluidService* fluid, SsaService* ssa, LoopSettings settings, RunManifest& stats);
  ~SplittingLoop();
  SplittingLoop(const SplittingLoop&) = delete;
  SplittingLoop& operator=(const SplittingLoop&) = delete;

  /// Continue from a restored state at time t after `steps` coupling steps.
  void resume_at(double t, std::uint64_t steps);
  /// Runs to the end (or stop_at, or a requested stop); writes a final
  /// checkpoint when checkpoints are on and the last one is not at the end.
  /// @return true when stopped early (stop_at or a stop request)
  bool run(const LoopHooks& hooks);

  [[nodiscard]] double time() const { return t_; }
  [[nodiscard]] std::uint64_t steps() const { return step_; }
  [[nodiscard]] bool overlapping() const { return overlap_; }
  /// The step controller (LoopSettings::tolerance), else null.
  [[nodiscard]] const StepController* controller() const { return control_.get(); }
  /// The controller's state and its inputs' samples (checkpoint blob; "" without
  /// a controller), and back (resume).
  [[nodiscard]] std::string control_state() const;
  void restore_control_state(const std::string& bytes);

 private:
  struct SsaJob;
  class Worker;
  void step(const CouplingStep& cs, bool defer_ssa);
  /// One step under the controller (controlled_step.cpp): tried from a snapshot of
  /// both services, redone shorter until accepted; returns the step taken.
  CouplingStep controlled_step(CouplingStep cs);
  std::vector<InputSample> start_samples();
  std::vector<InputSample> end_samples(const CouplingStep& cs, std::uint64_t events);
  SpeciesCounts back_transfer_counts();
  void run_ssa(SsaJob& job);
  void finish_ssa(const SsaJob& job);
  void drain();
  void drain_after_failure() noexcept;
  [[nodiscard]] double next_checkpoint_after(double t) const;

  FluidService* fluid_;
  SsaService* ssa_;
  LoopSettings s_;
  RunManifest& stats_;
  bool overlap_ = false;
  double t_ = 0.0;
  std::uint64_t step_ = 0;
  /// Copy numbers of s_.back_transfer after the last SSA stage (valid: has_counts_).
  SpeciesCounts counts_;
  bool has_counts_ = false;
  /// The body forces of this step's fluid stages (end time, length, forces), for the hook.
  struct StageForces {
    double t = 0, dt = 0;
    std::vector<BodyForceSample> forces;
  };
  std::vector<StageForces> stage_forces_;
  /// With a tolerance: the controller, the coupling inputs it watches (the fed-back
  /// copy numbers, then the frozen concentrations) and the frozen concentrations the
  /// last SSA stage received.
  std::unique_ptr<StepController> control_;
  std::vector<InputTrack> tracks_;
  SpeciesConcentrations last_frozen_;
  std::unique_ptr<SsaJob> pending_;  ///< an SSA stage running on worker_
  std::unique_ptr<Worker> worker_;   ///< declared last: joined first
};

}  // namespace sadr::orchestrator
