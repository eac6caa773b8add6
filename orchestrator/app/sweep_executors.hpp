// SPDX-License-Identifier: MIT
/// \file sweep_executors.hpp
/// (private) Executors of a sweep's runs: each runs `sadr sweep-task DIR`
/// for a list of run indices and returns when they have ended; the results
/// are in each run's result.json (SweepManifest::fold_outcomes).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "sadr/orchestrator/sweep_manifest.hpp"

namespace sadr::orchestrator {

/// Counts of one executor pass.
struct ExecutorReport {
  std::size_t started = 0;  ///< workers started (retries included)
};

/// This executable (for the worker command line).
std::string self_executable();

/// `workers` child processes at a time, each in its own process group, with
/// OMP_NUM_THREADS = cores / workers (unless set); a failed run is retried
/// up to m.retries times. SIGINT/SIGTERM are forwarded to the workers (they
/// checkpoint and stop). Updates m (and sweep.json) as runs end.
ExecutorReport run_local(SweepManifest& m, const std::filesystem::path& dir,
                         std::vector<std::size_t> todo, int workers, bool quiet);

/// One `sbatch --array` of the runs per round, a dependent aggregation job
/// (`sadr sweep --resume DIR --aggregate-only`), squeue polling until both
/// left the queue, then a new round for failed runs (up to m.retries).
/// Writes sweep.json only while none of its jobs run.
ExecutorReport run_slurm(SweepManifest& m, const std::filesystem::path& dir,
                         std::vector<std::size_t> todo, bool quiet);

}  // namespace sadr::orchestrator
