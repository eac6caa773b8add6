// SPDX-License-Identifier: MIT
/// \file commands.hpp
/// (private) What the subcommands share: signals, the plan, running one
/// realization with its services, and the checks before a run writes anything.
#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "sadr/orchestrator/coupled_run.hpp"
#include "sadr/orchestrator/ensemble_manifest.hpp"
#include "sadr/orchestrator/exit_codes.hpp"
#include "sadr/orchestrator/work_estimate.hpp"
#include "service_options.hpp"

namespace sadr::orchestrator {

/// SIGINT/SIGTERM set a flag (interrupt_requested()) that stops runs at a checkpoint.
void install_signal_handlers();
bool interrupt_requested();
/// The flag itself (RunOptions::interrupt, the ensemble pool).
std::atomic<bool>& interrupt_flag();

/// Prints the scene summary and the plan to stderr (nothing but warnings when o.quiet).
void print_plan(const Scene& scene, const Plan& plan, const ServiceOptions& o);
/// One realization into `out`, relaunching its services from the last
/// checkpoint up to o.restarts times when a service dies or stops answering.
RunResult run_realization(const Scene& scene, const Plan& plan, const ServiceOptions& o,
                          std::uint64_t realization, const std::filesystem::path& out,
                          const LoadedCheckpoint* resume, const RunOptions& base);
/// Realization `r` of an ensemble into `rd`, retried up to o.retries times
/// when it fails (docs/sweeps.md, faults): each retry resumes from the last
/// checkpoint when `from_checkpoint`, else starts at t = 0 with the failed
/// attempt's frames and checkpoints removed. `before_attempt` runs before
/// every attempt (e.g. to drop frames collected by base.on_frame). Returns the
/// last failure, or nothing when an attempt ended (done or interrupted) with
/// its result in `result`.
std::optional<FailedRealization> run_ensemble_member(const Scene& scene, const Plan& plan,
                                                     const ServiceOptions& o, int r,
                                                     const std::filesystem::path& rd,
                                                     bool from_checkpoint, const RunOptions& base,
                                                     const std::function<void()>& before_attempt,
                                                     RunResult& result);
/// Prints the table of failed realizations and how to resume; returns the exit code (3).
int report_failed_realizations(const std::filesystem::path& dir,
                               const std::vector<FailedRealization>& failed);

// Flow replay in an ensemble (flow_replay_pass.cpp).
/// DIR/flow_replay.bin.
std::filesystem::path flow_replay_path(const std::filesystem::path& dir);
/// The flow replay file of the ensemble in `dir`: an existing one (its fluid key
/// checked), else the fluid-only pass writes it. Returns "" when a stop was
/// requested during the pass (nothing written).
std::filesystem::path prepare_flow_replay(const Scene& scene, const Plan& plan,
                                          const ServiceOptions& o,
                                          const std::filesystem::path& dir);
/// What shared_flow_tape() found or did.
struct SharedFlowTape {
  std::filesystem::path path;  ///< the complete file to replay; "" = none (`stopped`, `reason`)
  bool recorded = false;       ///< this process recorded it
  bool stopped = false;        ///< a stop was requested while waiting or recording
  std::string reason;          ///< why there is none when not stopped (no file locks there)
};
/// The flow replay file `path` shared by runs that may start at once (a sweep's runs of one
/// fluid, the tasks of an array): an existing complete one (its fluid key checked), else
/// the first run to take the exclusive lock `path` with extension .lock records it and the
/// others wait on the lock, then replay it. A recorder that dies releases the lock; its
/// partial file is recorded again by the next.
SharedFlowTape shared_flow_tape(const Scene& scene, const Plan& plan, const ServiceOptions& o,
                                const std::filesystem::path& path);
/// The realization in `realization_dir` has a checkpoint that replays the flow.
bool checkpoint_replays_flow(const std::filesystem::path& realization_dir);

// Checks and settings before a run (run_checks.cpp).
/// OpenMP threads the fluid will use: --fluid-threads, else SADR_FLUID_THREADS,
/// else OMP_NUM_THREADS (its first value), else every hardware thread.
int fluid_threads(const ServiceOptions& o, unsigned hardware_threads);
/// Per-service thread counts for the services launched here, then the overlap decision.
void configure_threads_and_overlap(Plan& plan, const ServiceOptions& o, int jobs);
/// estimate_work() with the backend's sub-steps at t = 0 when they can be computed here.
WorkEstimate estimate_with_backend(const Scene& scene, const Plan& plan,
                                   const std::filesystem::path& out, int realizations, int jobs);
/// The work estimate, printed with the plan, then its limits: hard ones always
/// refuse; soft ones refuse unless --allow-large (then they are warnings).
void check_work(const Scene& scene, const Plan& plan, const ServiceOptions& o,
                const std::filesystem::path& out, int realizations, int jobs);
/// --stop-at T: finite (the parser checks >= 0) and before the scene's end.
void check_stop_at(const ServiceOptions& o, const Scene& scene, double from);

/// The same table as `sadr summary` at the end of `sadr run` / `sadr resume`
/// (stderr; nothing when `quiet`). A summary that cannot be made is a warning.
void summarize_at_end(const std::filesystem::path& dir, bool quiet);
/// Combines DIR/realization_*/frames/*.csv into DIR/ensemble/ (mean, variance).
int combine_ensemble(const std::filesystem::path& dir);
/// `sadr resume DIR` for an ensemble folder: runs or resumes every realization
/// that did not finish, then recombines DIR/ensemble/ from the CSV frames.
int resume_ensemble(const ServiceOptions& options, const std::filesystem::path& dir);

}  // namespace sadr::orchestrator
