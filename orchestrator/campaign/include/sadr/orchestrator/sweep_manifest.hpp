// SPDX-License-Identifier: MIT
/// \file sweep_manifest.hpp
/// The sweep manifest (SWEEP_DIR/sweep.json, docs/sweeps.md): every point
/// (its overrides and seed), every run (point, realization, seed, directory,
/// state, exit code, reason, attempts, what was kept) and the aggregates.
/// Only the process that drives the sweep writes it (atomically); a worker
/// writes only its run's result.json, which the driver folds in.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "sadr/orchestrator/sweep_spec.hpp"

namespace sadr::orchestrator {

enum class RunState { kPending, kRunning, kOk, kFailed, kInterrupted };
std::string_view to_string(RunState state);

/// What a worker leaves in its run directory when it ends (result.json).
struct RunOutcome {
  RunState state = RunState::kFailed;
  int exit_code = 0;
  std::string reason;      ///< "" when ok; the error message otherwise
  std::string scene_hash;  ///< of the effective scene that ran
  bool resumed = false;    ///< continued from a checkpoint
  int attempts = 1;        ///< workers started for this run so far (this one included)
  /// CPU seconds (user + sys) of this attempt's worker and the services it
  /// started and reaped; < 0 when not measured.
  double cpu_s = -1;
  bool flow_replay = false;    ///< the run replayed its fluid (docs/sweeps.md, flow replay)
  bool flow_recorded = false;  ///< ... and this attempt recorded the file
  std::string fluid_key;       ///< fluid key of a replayed run ("" otherwise)
};
/// Writes `dir`/result.json atomically.
void write_run_outcome(const std::filesystem::path& dir, const RunOutcome& outcome);
/// Reads `dir`/result.json; nullopt if absent or unreadable.
std::optional<RunOutcome> read_run_outcome(const std::filesystem::path& dir);

struct SweepRun {
  std::size_t index = 0;  ///< point * realizations + realization (the array index)
  std::size_t point = 0;
  std::size_t realization = 0;
  std::uint64_t seed = 0;  ///< the seed the run uses: mix_seed(point seed, realization)
  std::string dir;         ///< relative to the sweep directory: runs/p0000_r0000
  RunState state = RunState::kPending;
  int exit_code = 0;
  std::string reason;
  int attempts = 0;          ///< times a worker was started for it
  std::string scene_hash;    ///< of its effective scene (from result.json)
  std::string kept = "all";  ///< "all" or "run.json" (frames removed after aggregation)
};

/// Flow replay of one point, decided by the driver (sadr sweep) and read by each sweep-task.
struct PointFlow {
  bool replay = false;    ///< its runs replay the file flow_tape_file(fluid_key)
  std::string fluid_key;  ///< fluid_key() of the point's scene ("" when its fluid cannot replay)
  std::string reason;     ///< why it does, or why not
};

struct SweepManifest {
  std::string sweep_file;
  std::string base_scene;
  std::uint64_t seed = 0;  ///< sweep seed
  std::size_t realizations = 1;
  KeepPolicy keep = KeepPolicy::kAggregates;
  ExecutorSpec executor;
  int retries = 1;
  std::vector<std::string> parameters;
  std::vector<SweepPoint> points;
  std::vector<std::uint64_t> point_seeds;  ///< mix_seed(seed, point)
  std::vector<SweepRun> runs;
  nlohmann::json aggregates = nlohmann::json::object();  ///< per point: dir, realizations, notes
  /// Per point (points[i]["flow_replay"] in sweep.json); empty: not decided, every run
  /// steps its own fluid.
  std::vector<PointFlow> flows;

  /// Folds each run's result.json into `runs` (state, exit code, reason,
  /// attempts, hash). A result left "running" by a worker that is gone
  /// becomes "interrupted" (resumed from its checkpoint when run again).
  void fold_outcomes(const std::filesystem::path& dir);
  /// fold_outcomes() of one run.
  void fold_outcome(const std::filesystem::path& dir, std::size_t index);
  /// Same points, realizations and seeds (what makes the runs' results).
  [[nodiscard]] bool same_runs(const SweepManifest& other) const;

  /// Points x realizations of `spec`, all pending. @param seed the sweep seed
  static SweepManifest plan(const SweepSpec& spec, std::uint64_t seed);
  /// The overrides of run `r`'s scene: its point's, then `seed=<point seed>`.
  [[nodiscard]] std::vector<SceneOverride> overrides_of(const SweepRun& r) const;
  /// The run of array index `index`. @throws InvalidArgument if out of range.
  [[nodiscard]] const SweepRun& run(std::size_t index) const;

  [[nodiscard]] nlohmann::json to_json() const;
  static SweepManifest from_json(const nlohmann::json& j, const std::string& source);
  /// `dir`/sweep.json, atomically.
  void write(const std::filesystem::path& dir) const;
  /// @throws InvalidArgument if `dir`/sweep.json is missing or malformed.
  static SweepManifest read(const std::filesystem::path& dir);
};

/// "points/p0003": where point 3's aggregates go, relative to the sweep directory.
std::string point_dir(std::size_t point);

/// "flows/0123456789abcdef.bin": the flow replay file of fluid key `key`
/// ("fnv1a64:0123456789abcdef"), relative to the sweep directory.
std::string flow_tape_file(const std::string& key);

inline constexpr std::string_view kSweepManifestName = "sweep.json";

}  // namespace sadr::orchestrator
