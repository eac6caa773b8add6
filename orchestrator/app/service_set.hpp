// SPDX-License-Identifier: MIT
/// \file service_set.hpp
/// The services of one realization, however they run: child processes over
/// ipc (default), threads over inproc (--embedded), or already running
/// elsewhere (--fluid/--ssa ENDPOINT). This is the composition root: the
/// only place that links the service libraries.
#pragma once

#include <atomic>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "sadr/orchestrator/coupled_run.hpp"
#include "sadr/orchestrator/plan.hpp"
#include "sadr/orchestrator/service_process.hpp"
#include "sadr/wire/rpc.hpp"

namespace sadr::orchestrator {

enum class ServiceMode { kProcesses, kEmbedded, kRemote };
std::string_view to_string(ServiceMode mode);

/// Removes what runs that no longer exist left behind (kill -9): geometry
/// segments /dev/shm/sadr-geometry-<pid>-* and run directories or sockets
/// <tmp>/sadr-run-<pid>-*, <tmp>/sadr-<pid>-* of this user whose pid is gone.
/// Returns how many were removed.
std::size_t remove_traces_of_dead_runs();

class ServiceSet {
 public:
  /// Starts what `plan` needs. `remote` holds the endpoints for kRemote.
  /// `tag` makes ipc/inproc names unique (e.g. the realization index).
  ServiceSet(ServiceMode mode, const Plan& plan, const ServiceEndpoints& remote,
             const std::string& tag);
  ~ServiceSet();
  ServiceSet(const ServiceSet&) = delete;
  ServiceSet& operator=(const ServiceSet&) = delete;

  [[nodiscard]] const ServiceEndpoints& endpoints() const { return endpoints_; }
  /// Throws sadr::Error(kUnavailable) naming a child process that has exited.
  /// Thread-safe (the overlapped loop waits for both services at once).
  void check_alive();
  /// Asks the services to shut down (processes: then waits / terminates).
  void stop();

 private:
  ServiceMode mode_;
  ServiceEndpoints endpoints_;
  std::vector<std::unique_ptr<ServiceProcess>> processes_;
  std::vector<std::unique_ptr<wire::RpcServer>> servers_;
  std::vector<std::unique_ptr<wire::RequestHandler>> handlers_;
  std::vector<std::thread> threads_;
  std::atomic<bool> stop_threads_{false};
  std::vector<std::string> ipc_files_;
  std::string secret_;  ///< per-run secret of the services launched here (SADR_RUN_SECRET)
  std::filesystem::path run_dir_;  ///< <tmp>/sadr-run-<pid>-XXXXXX (0700): the ipc sockets
  std::mutex alive_mutex_;         ///< check_alive() from the main thread and the SSA worker
};

}  // namespace sadr::orchestrator
