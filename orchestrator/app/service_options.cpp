// SPDX-License-Identifier: MIT
#include "service_options.hpp"

#include <cstdio>

#include "cli.hpp"
#include "sadr/orchestrator/exit_codes.hpp"

namespace sadr::orchestrator {

void add_service_options(CLI::App* cmd, ServiceOptions& o) {
  cmd->add_flag("--embedded", o.embedded,
                "run the services as threads in this process (inproc transport) instead of "
                "child processes");
  cmd->add_option("--fluid", o.remote.fluid,
                  "endpoint of a running fluid_service (e.g. tcp://host:5555); with --ssa, "
                  "nothing is launched");
  cmd->add_option("--ssa", o.remote.ssa, "endpoint of a running ssa_service");
  cmd->add_option("--key", o.remote_keys.key,
                  "CURVE key pair of this sadr (sadr keygen FILE) for --fluid/--ssa tcp "
                  "endpoints: encrypted, and only services holding the --server-key answer");
  cmd->add_option("--server-key", o.remote_keys.server_key,
                  "public key of the services (40 characters, or their FILE.pub)");
  cmd->add_option("--fluid-server-key", o.remote_keys.fluid_server_key,
                  "fluid_service's public key, when it differs from --server-key");
  cmd->add_option("--ssa-server-key", o.remote_keys.ssa_server_key,
                  "ssa_service's public key, when it differs from --server-key");
  cmd->add_flag("!--no-shared-memory", o.shared_geometry,
                "send the per-step particle geometry inline in the messages instead of "
                "through a shared-memory segment (the default for services launched here)");
  cmd->add_option("--timeout", o.timeout_s, "seconds to wait for a service reply")
      ->check(finite_range(1e-3, 1e6, "0.001 to 1e6 seconds"))
      ->capture_default_str();
  cmd->add_option("--restart-on-failure", o.restarts,
                  "relaunch services that die or hang, from the last checkpoint, up to N times")
      ->check(CLI::Range(0, 1000000));
  cmd->add_option("--stop-at", o.stop_at,
                  "write a checkpoint and stop at this simulated time (resume later)")
      ->check(finite_range(0.0, 1e300, "a finite time >= 0 (and <= the scene's time.end)"));
  cmd->add_option("-o,--output", o.output,
                  "output directory (default: output.directory of the scene, else "
                  "runs/<name>-<UTC time>)");
  auto* overlap_on = cmd->add_flag_callback(
      "--overlap", [&o] { o.overlap = OverlapRequest::kOn; },
      "run the SSA stage of coupling step k while the fluid computes step k+1 even "
      "without a spare core (default: only when each realization has a core to spare "
      "for the SSA: hardware threads >= fluid threads + 1; see docs/cli.md)");
  auto* overlap_off = cmd->add_flag_callback(
      "--no-overlap", [&o] { o.overlap = OverlapRequest::kOff; },
      "always run the fluid and SSA stages one after the other");
  overlap_on->excludes(overlap_off);
  cmd->add_option("--fluid-threads", o.fluid_threads,
                  "OpenMP threads of fluid_service (default: OMP_NUM_THREADS, else all "
                  "cores); sets SADR_FLUID_THREADS for the services launched here")
      ->check(CLI::Range(1, 4096));
  cmd->add_option("--ssa-threads", o.ssa_threads,
                  "OpenMP threads of ssa_service's graph rebuild (default: OMP_NUM_THREADS, "
                  "else all cores); sets SADR_SSA_THREADS for the services launched here")
      ->check(CLI::Range(1, 4096));
  cmd->add_flag("-q,--quiet", o.quiet,
                "no progress display, plan or info lines (warnings and errors only; "
                "--log-level overrides)");
  cmd->add_flag("--no-progress", o.no_progress, "no progress display (plan and logs stay)");
  cmd->add_flag("--allow-large", o.allow_large,
                "run a scene whose work estimate is above the soft limits (long runs, "
                "large output, more than half the memory; see docs/cli.md)");
  cmd->add_option("--log-level", o.log_level, "error|warn|info|debug")
      ->check(CLI::IsMember({"error", "warn", "info", "debug"}));
}

void add_retries_option(CLI::App* cmd, ServiceOptions& o) {
  cmd->add_option("--retries", o.retries,
                  "ensembles: run a failed realization again up to N more times (as a "
                  "sweep's retries; default 1)")
      ->check(CLI::Range(0, 100));
}

void add_flow_replay_option(CLI::App* cmd, ServiceOptions& o) {
  cmd->add_flag("--no-flow-replay", o.no_flow_replay,
                "ensembles and array tasks: step the fluid in every realization, even when it "
                "is the same in all of them (default: computed once and replayed when the "
                "fluid draws no random numbers and reads nothing of the SSA; docs/cli.md)");
}

int resolve_service_mode(ServiceOptions& o) {
  apply_log_level(o.quiet, o.log_level);
  if (o.embedded) o.mode = ServiceMode::kEmbedded;
  if (!o.remote.fluid.empty() || !o.remote.ssa.empty()) {
    if (o.embedded) {
      std::fprintf(stderr, "sadr: --embedded cannot be combined with --fluid/--ssa\n");
      return kExitUsage;
    }
    o.mode = ServiceMode::kRemote;
  }
  return kExitOk;
}

}  // namespace sadr::orchestrator
