// SPDX-License-Identifier: MIT
/// \file run_manifest.hpp
/// The run manifest (run.json in each output folder): what was run, with
/// which scene (hash), seed and build, how long each part took, and the plan.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace sadr::orchestrator {

/// The folder of realization r of an ensemble inside its output folder: "realization_NNNN"
/// (four digits at least), the one spelling that `run -r`, `--realization`, `ensemble`,
/// `summary` and the Python package read.
[[nodiscard]] std::string realization_dir_name(std::uint64_t r);
/// Whether a folder name is that of a realization (realization_dir_name of some r).
[[nodiscard]] bool is_realization_dir_name(std::string_view name);

struct RunManifest {
  std::string scene_path;
  std::string scene_hash;  ///< content_hash() of the effective scene (file bytes + overrides)
  std::vector<std::string> overrides;  ///< `--set` PATH=VALUE applied to the file, in order
  std::uint64_t scene_seed = 0;
  std::uint64_t realization = 0;
  std::uint64_t seed = 0;         ///< realization seed actually used
  std::string sadr_version;       ///< defaults to sadr::kVersion
  unsigned protocol_version = 0;  ///< defaults to sadr::kProtocolVersion
  std::string mode;               ///< "processes", "embedded", "remote"
  /// Run-time environment that changes speed, not results: OMP_NUM_THREADS,
  /// OMP_WAIT_POLICY, GOMP_SPINCOUNT as this process saw them ("" = unset); filled by
  /// RunManifest().
  std::map<std::string, std::string> environment;
  std::string started_utc;  ///< ISO 8601, e.g. "2026-11-22T03:00:00Z"
  std::string finished_utc;
  std::string status = "running";  ///< "running", "ok", "failed: <reason>", "interrupted"
  std::uint64_t steps = 0;         ///< coupling steps completed
  /// Coupling steps whose SSA stage ran while the fluid computed the next step
  /// (plan.overlap); the others ran their stages one after the other.
  std::uint64_t overlapped_steps = 0;
  /// Fluid sub-steps taken by this invocation (a resumed run counts from the resume):
  /// with `timings_s` and the steps done here, how many sub-steps a coupling step costs.
  std::uint64_t fluid_substeps = 0;
  /// What the fluid backend reported after init (InitReply; {} if nothing): stable_time_step
  /// and limiting_criterion (its binding stability limit at t = 0), max_substep (the longest
  /// sub-step it takes from there; null: one per call) and substep_criterion (what sets it).
  nlohmann::json fluid_at_t0 = nlohmann::json::object();
  /// The smallest binding stability limit the fluid's sub-steps met in this invocation (the
  /// limits follow the state, so it can be far below fluid_at_t0's): {stable_time_step,
  /// limiting_criterion, time (the end of the coupling stage that met it)}; {} if none bound.
  /// A forced sub-step (fluid.force_time_step) at or below it keeps to every limit of the run.
  nlohmann::json fluid_smallest_limit = nlohmann::json::object();
  /// Takes a fluid stage's smallest limit `dt` [time] (ignored unless finite and > 0).
  void note_fluid_limit(double dt, const std::string& criterion, double time);
  /// SSA events (reactions + diffusion jumps) of this invocation, as fluid_substeps.
  std::uint64_t ssa_events = 0;
  /// Molecules the adaptive SSA moved by leaps (ssa.method adaptive); left out of run.json when 0.
  std::uint64_t ssa_leaped_molecules = 0;
  double time = 0.0;  ///< simulated time reached [time]
  /// Wall-clock seconds per part: "fluid" (fluid calls), "fluid_compute" (inside
  /// the service), "ssa" (SSA calls), "ssa_graph", "ssa_nsm" (inside the
  /// service), "transfer" (geometry hand-over), "coupling_loop" (the whole loop,
  /// frames and checkpoints included), "ssa_wait" (main thread on SSA stages
  /// outside a fluid call: the SSA time not hidden by the overlap), "init",
  /// "output", "checkpoint", ...
  std::map<std::string, double> timings_s;
  std::vector<std::string> frames;  ///< frame files written, in order
  nlohmann::json plan;              ///< Plan::to_json()
  /// Forces on bodies (scene fluid.body_forces): BodyForceLog::summary(); left out of run.json
  /// when empty.
  nlohmann::json body_forces = nlohmann::json::object();
  /// The error-controlled coupling step (time.tolerance), over the whole run (a resumed
  /// run continues the counts): accepted, rejected, unestimated, over_tolerance,
  /// smallest_step, largest_step, largest_error, next_step; left out of run.json when empty.
  nlohmann::json step_control = nlohmann::json::object();

  RunManifest();
  [[nodiscard]] nlohmann::json to_json() const;
  /// Writes to_json() to `path` atomically (pretty-printed).
  void write(const std::filesystem::path& path) const;
};

/// The `overrides` of `run_dir`/run.json ({} if the file or the key is absent).
/// @throws sadr::InvalidArgument if run.json exists but cannot be read as JSON.
std::vector<std::string> read_run_overrides(const std::filesystem::path& run_dir);

/// Current UTC time as ISO 8601 ("YYYY-MM-DDTHH:MM:SSZ").
std::string utc_now_iso8601();

}  // namespace sadr::orchestrator
