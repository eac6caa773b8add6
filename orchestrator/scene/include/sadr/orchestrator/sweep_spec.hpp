// SPDX-License-Identifier: MIT
/// \file sweep_spec.hpp
/// A sweep file (docs/sweeps.md): a base scene, parameters (a grid, zipped
/// lists or explicit points; each a scene override path), R realizations per
/// point, the executor, retries and what to keep; expanded into points.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "sadr/orchestrator/scene_override.hpp"

namespace sadr::orchestrator {

enum class KeepPolicy {
  kAll,         ///< every run's frames
  kAggregates,  ///< aggregates, plus all files of realization 0 of each point
};

struct ExecutorSpec {
  std::string type = "local";            ///< "local" or "slurm"
  int workers = 0;                       ///< local: parallel runs (0 = number of cores)
  int cpus_per_task = 1;                 ///< slurm: --cpus-per-task of each array task
  std::string partition;                 ///< slurm: --partition ("" = the cluster's default)
  std::vector<std::string> sbatch_args;  ///< slurm: extra sbatch arguments
  double poll_seconds = 2.0;             ///< slurm: squeue polling period [s]
};

/// One point of the sweep: the overrides that make its scene.
struct SweepPoint {
  std::size_t index = 0;
  /// One override per parameter, in the order of SweepSpec::parameters.
  std::vector<SceneOverride> overrides;
};

struct SweepSpec {
  std::filesystem::path source;         ///< the sweep file
  std::filesystem::path base_scene;     ///< absolute (relative paths are relative to the file)
  std::vector<std::string> parameters;  ///< override paths, in the order of the columns
  std::vector<SweepPoint> points;
  std::size_t realizations = 1;
  /// Per-run seeds derive from this; nullopt = the base scene's `seed`.
  std::optional<std::uint64_t> seed;
  ExecutorSpec executor;
  int retries = 1;  ///< extra attempts of a failed run (per invocation of the sweep)
  KeepPolicy keep = KeepPolicy::kAggregates;
  std::string output;  ///< output directory from the file ("" = the CLI's choice)
};

/// Reads and checks a sweep file: unknown keys (with the nearest valid one),
/// value types, equal lengths of zipped lists, at least one point. Parameter
/// paths are checked for syntax here; their values are validated when each
/// point's scene is loaded (SweepSpec is not enough for that: see
/// validate_points() in the app).
/// @throws sadr::InvalidArgument naming the file, line and key.
SweepSpec load_sweep_spec(const std::filesystem::path& path);
SweepSpec parse_sweep_spec(const std::string& text, const std::filesystem::path& source);

std::string_view to_string(KeepPolicy keep);

}  // namespace sadr::orchestrator
