// SPDX-License-Identifier: MIT
/// \file service_options.hpp
/// (private) The options of `sadr run` and `sadr resume` about the services
/// and the realization loop, shared by the code that runs realizations.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

#include "sadr/orchestrator/coupled_run.hpp"
#include "service_set.hpp"

namespace sadr::orchestrator {

/// CURVE for --fluid/--ssa (keys_command.cpp; docs/cli.md, "Security").
struct RemoteKeys {
  std::string key;               ///< --key: this side's key pair (sadr keygen)
  std::string server_key;        ///< --server-key: the services' public key (text or file)
  std::string fluid_server_key;  ///< --fluid-server-key: fluid_service's, if it differs
  std::string ssa_server_key;    ///< --ssa-server-key: ssa_service's, if it differs
};

struct ServiceOptions {
  std::string output;  ///< output directory ("" = default)
  ServiceMode mode = ServiceMode::kProcesses;
  bool embedded = false;    ///< --embedded (mode is set by resolve_service_mode)
  ServiceEndpoints remote;  ///< --fluid / --ssa
  RemoteKeys remote_keys;   ///< --key / --server-key (CURVE to remote services)
  /// Geometry fluid -> ssa through shared memory when the services run here
  /// (off: --no-shared-memory).
  bool shared_geometry = true;
  int restarts = 0;          ///< --restart-on-failure N
  int retries = 1;           ///< --retries N: extra attempts of a failed realization (-r, resume)
  double timeout_s = 120;    ///< per service call
  double stop_at = -1;       ///< checkpoint and stop at this simulated time (< 0: never)
  bool quiet = false;        ///< no progress display, plan or info lines
  bool no_progress = false;  ///< --no-progress: no progress display (the plan stays)
  bool allow_large = false;  ///< --allow-large: lift the soft limits of the work estimate
  /// --overlap / --no-overlap: SSA step k at the same time as fluid step k + 1.
  OverlapRequest overlap = OverlapRequest::kAuto;
  bool no_flow_replay = false;  ///< --no-flow-replay: every realization steps its fluid
  int fluid_threads = 0;        ///< --fluid-threads (0 = OpenMP's default); SADR_FLUID_THREADS
  int ssa_threads = 0;          ///< --ssa-threads (0 = OpenMP's default); SADR_SSA_THREADS
  std::string log_level = "info";
};

/// The service options of run and resume (--embedded ... --log-level).
void add_service_options(CLI::App* cmd, ServiceOptions& o);
/// --retries N (run, resume).
void add_retries_option(CLI::App* cmd, ServiceOptions& o);
/// --no-flow-replay (run, resume).
void add_flow_replay_option(CLI::App* cmd, ServiceOptions& o);
/// After parsing: the log level, then the mode from --embedded and --fluid/--ssa.
/// Returns kExitUsage (with a message) for --embedded with --fluid/--ssa, else kExitOk.
int resolve_service_mode(ServiceOptions& o);

/// Registers the CURVE credentials of --key/--server-key for the remote
/// endpoints; refuses keys without remote services and one without the other
/// (keys_command.cpp).
void use_remote_keys(const ServiceOptions& options);

}  // namespace sadr::orchestrator
