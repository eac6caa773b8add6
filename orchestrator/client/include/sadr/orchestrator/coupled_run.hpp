// SPDX-License-Identifier: MIT
/// \file coupled_run.hpp
/// One realization of a scene: the Lie/Strang coupling loop between
/// fluid_service and ssa_service (docs/method.md section 1), with frames at exactly the
/// requested times, periodic and on-signal checkpoints, a progress display,
/// and resume from a checkpoint. The services are already running; this
/// code only needs their endpoints.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <string>

#include "sadr/orchestrator/checkpoint.hpp"
#include "sadr/orchestrator/frame_writers.hpp"
#include "sadr/orchestrator/plan.hpp"
#include "sadr/orchestrator/scene.hpp"

namespace sadr::orchestrator {

struct ServiceEndpoints {
  std::string fluid;  ///< "" when the plan needs no fluid_service
  std::string ssa;    ///< "" when the plan needs no ssa_service
};

struct RunOptions {
  std::filesystem::path output_dir;  ///< frames, run.json, checkpoint/
  std::uint64_t realization = 0;
  std::string mode = "processes";  ///< for the manifest: processes | embedded | remote
  /// The services run on this host (launched here): hand the per-step geometry
  /// from fluid_service to ssa_service through a shared-memory segment
  /// (sadr/wire/shared_geometry.hpp) instead of inline in the messages.
  bool shared_geometry = false;
  std::chrono::milliseconds timeout{std::chrono::seconds(120)};  ///< per service call
  bool progress = true;                          ///< progress bar (terminal) or periodic lines
  std::string progress_label;                    ///< prefix of progress lines ("" = none)
  const std::atomic<bool>* interrupt = nullptr;  ///< set by SIGINT/SIGTERM: checkpoint and stop
  /// Called while waiting for a service; throws if a service process died.
  std::function<void()> liveness;
  /// Resume from this checkpoint instead of starting at t = 0.
  const LoadedCheckpoint* resume = nullptr;
  /// Checkpoint and stop at the end of the first coupling step that reaches
  /// this simulated time (splits long runs into scheduler slots) [time].
  double stop_at = std::numeric_limits<double>::infinity();
  /// Flow replay file (flow_replay.hpp): the fluid's answers come from it and no
  /// fluid_service is used ("" = step the fluid).
  std::filesystem::path flow_replay;
  /// Called after every frame with its output index, time and species columns
  /// (ensemble statistics).
  std::function<void(std::size_t, double, std::span<const SpeciesColumn>)> on_frame;
};

struct RunResult {
  bool interrupted = false;
  std::uint64_t steps = 0;  ///< coupling steps completed
  double time = 0.0;        ///< simulated time reached
  std::size_t frames = 0;   ///< frames written by this call
  std::optional<std::filesystem::path> last_checkpoint;
};

/// Runs (or resumes) one realization. Throws sadr::Error naming the failing
/// service; the last good checkpoint (if any) stays in output_dir/checkpoint.
RunResult run_coupled(const Scene& scene, const Plan& plan, const ServiceEndpoints& endpoints,
                      const RunOptions& options);

}  // namespace sadr::orchestrator
