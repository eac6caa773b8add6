// SPDX-License-Identifier: MIT
/// \file commands.hpp
/// The orchestrator's subcommands (run, resume, validate) and exit codes.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "sadr/orchestrator/coupled_run.hpp"
#include "service_set.hpp"

namespace sadr::orchestrator {

/// Exit codes of the `sadr` CLI (documented in docs/scene-format.md and README.md).
enum ExitCode : int {
  kExitOk = 0,
  kExitInvalidInput = 1,
  kExitUsage = 2,
  kExitServiceFailure = 3,
  kExitNumericalFailure = 4,
  kExitIoFailure = 5,
  kExitInterrupted = 130,
};

/// CURVE for --fluid/--ssa (keys_command.cpp; docs/cli.md, "Security").
struct RemoteKeys {
  std::string key;               ///< --key: this side's key pair (sadr keygen)
  std::string server_key;        ///< --server-key: the services' public key (text or file)
  std::string fluid_server_key;  ///< --fluid-server-key: fluid_service's, if it differs
  std::string ssa_server_key;    ///< --ssa-server-key: ssa_service's, if it differs
};

struct CliOptions {
  std::string scene;       ///< scene file (run, validate)
  std::string checkpoint;  ///< checkpoint.json or its directory (resume)
  std::string output;      ///< output directory ("" = default)
  bool force = false;      ///< overwrite a non-empty output directory
  ServiceMode mode = ServiceMode::kProcesses;
  ServiceEndpoints remote;  ///< --fluid / --ssa
  RemoteKeys remote_keys;   ///< --key / --server-key (CURVE to remote services)
  /// Geometry fluid -> ssa through shared memory when the services run here
  /// (off: --no-shared-memory).
  bool shared_geometry = true;
  int realizations = 1;
  int jobs = 0;              ///< parallel realizations (0 = number of cores)
  int restarts = 0;          ///< --restart-on-failure N
  int retries = 1;           ///< --retries N: extra attempts of a failed realization (-r, resume)
  double timeout_s = 120;    ///< per service call
  double stop_at = -1;       ///< checkpoint and stop at this simulated time (< 0: never)
  bool quiet = false;        ///< no progress display, plan or info lines
  bool no_progress = false;  ///< --no-progress: no progress display (the plan stays)
  bool allow_large = false;  ///< --allow-large: lift the soft limits of the work estimate
  bool strict = false;       ///< validate --strict: a scene warning is an error
  bool dry_run = false;      ///< sweep --dry-run: check and list the runs, start nothing
  /// --overlap / --no-overlap: SSA step k at the same time as fluid step k + 1.
  OverlapRequest overlap = OverlapRequest::kAuto;
  int fluid_threads = 0;  ///< --fluid-threads (0 = OpenMP's default); SADR_FLUID_THREADS
  int ssa_threads = 0;    ///< --ssa-threads (0 = OpenMP's default); SADR_SSA_THREADS
  /// Run only this realization (a cluster array task); "" = all. "env" takes
  /// the index from SLURM_ARRAY_TASK_ID or JOB_COMPLETION_INDEX.
  std::string realization;
  std::string directory;               ///< ensemble: the output directory to combine
  std::vector<std::string> overrides;  ///< --set PATH=VALUE (run, validate)
  std::string sweep;                   ///< sweep: the sweep file ("" with --resume)
  std::string resume_dir;              ///< sweep --resume DIR
  bool aggregate_only = false;         ///< sweep: only fold results and aggregate
  int workers = 0;                     ///< sweep: local workers (0 = the file's, else cores)
  std::string executor;                ///< sweep --executor local|slurm ("" = the file's)
  std::string index;                   ///< sweep-task --index ("" = from the environment)
};

int cmd_validate(const CliOptions& options);
/// `sadr geometry SCENE -o DIR`: the particles of a `geometry` section (geometry_command.cpp).
int cmd_geometry(const CliOptions& options);
/// `sadr keygen FILE` writes a CURVE key pair (FILE, 0600) and FILE.pub;
/// `--show` prints the public key of FILE (keys_command.cpp).
int cmd_keygen(const std::string& file, bool show);
/// Registers the CURVE credentials of --key/--server-key for the remote
/// endpoints; refuses keys without remote services and one without the other.
void use_remote_keys(const CliOptions& options);
/// `sadr backends [--markdown]` (backends_command.cpp).
int cmd_backends(bool markdown);
int cmd_run(const CliOptions& options);
int cmd_resume(const CliOptions& options);
/// Combines DIR/realization_*/frames/*.csv into DIR/ensemble/ (mean, variance).
int cmd_ensemble(const CliOptions& options);

/// `sadr summary DIR`: what a run or an ensemble did (summary_command.cpp).
int cmd_summary(const CliOptions& options);
/// The same table at the end of `sadr run` / `sadr resume` (stderr; nothing
/// when `quiet`). A summary that cannot be made is a warning, not a failure.
void summarize_at_end(const std::filesystem::path& dir, bool quiet);

/// `sadr sweep SWEEP.yaml` / `sadr sweep --resume DIR` (sweep_command.cpp).
int cmd_sweep(const CliOptions& options);
/// `sadr sweep-task DIR [--index I]`: one run of a sweep (sweep_task.cpp).
int cmd_sweep_task(const CliOptions& options);

/// SIGINT/SIGTERM set a flag (interrupt_requested()) that stops runs at a checkpoint.
void install_signal_handlers();
bool interrupt_requested();
/// Prints the scene summary and the plan to stderr.
void print_plan(const Scene& scene, const Plan& plan, const CliOptions& o);
/// One realization into `out`, relaunching its services from the last
/// checkpoint up to o.restarts times when a service dies or stops answering.
RunResult run_realization(const Scene& scene, const Plan& plan, const CliOptions& o,
                          std::uint64_t realization, const std::filesystem::path& out,
                          const LoadedCheckpoint* resume, const RunOptions& base);

/// Maps an exception to an exit code and prints it ("sadr: error: ...").
int report_failure(const std::exception& e);
/// The exit code of an exception (see ExitCode), without printing.
int exit_code_of(const std::exception& e);

/// A realization of `sadr run -r R` that failed (the others go on).
struct FailedRealization {
  int realization = 0;
  int exit_code = 0;
  std::string reason;
  int attempts = 1;  ///< attempts made (1 + the retries used)
};
/// Realization `r` of an ensemble into `rd`, retried up to o.retries times
/// when it fails (docs/sweeps.md, faults): each retry resumes from the last
/// checkpoint when `from_checkpoint`, else starts at t = 0 with the failed
/// attempt's frames and checkpoints removed. `before_attempt` runs before
/// every attempt (e.g. to drop frames collected by base.on_frame). Returns the
/// last failure, or nothing when an attempt ended (done or interrupted) with
/// its result in `result`.
std::optional<FailedRealization> run_ensemble_member(const Scene& scene, const Plan& plan,
                                                     const CliOptions& o, int r,
                                                     const std::filesystem::path& rd,
                                                     bool from_checkpoint, const RunOptions& base,
                                                     const std::function<void()>& before_attempt,
                                                     RunResult& result);
/// DIR/ensemble.json: scene, overrides, R and the failed realizations, for
/// `sadr resume DIR` (ensemble_command.cpp).
void write_ensemble_manifest(const std::filesystem::path& dir, const Scene& scene, int realizations,
                             int retries, const std::vector<FailedRealization>& failed);
/// Prints the table of failed realizations and how to resume; returns the exit code (3).
int report_failed_realizations(const std::filesystem::path& dir,
                               const std::vector<FailedRealization>& failed);
/// `sadr resume DIR` for an ensemble folder: runs or resumes every realization
/// that did not finish, then recombines DIR/ensemble/ from the CSV frames.
int resume_ensemble(const CliOptions& options, const std::filesystem::path& dir);

}  // namespace sadr::orchestrator
