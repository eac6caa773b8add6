// SPDX-License-Identifier: MIT
/// \file service_process.hpp
/// A service executable running as a child process (RAII).
///
/// The child gets SIGTERM when the orchestrator dies (PR_SET_PDEATHSIG), so no
/// orphan services are left behind. It announces its endpoint with one stdout
/// line "SADR_ENDPOINT <url>"; its stderr (logs) is inherited.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <string>
#include <vector>

namespace sadr::orchestrator {

class ServiceProcess {
 public:
  /// Starts `executable args...` and waits up to `startup_timeout` for the
  /// endpoint line. Throws sadr::Error(kUnavailable) naming `name` if the
  /// executable is missing, exits early, or does not announce in time.
  /// `env` ("NAME=value") is added to the child's environment (not its
  /// command line), e.g. the run's SADR_RUN_SECRET.
  ServiceProcess(std::string executable, std::vector<std::string> args, std::string name,
                 std::chrono::milliseconds startup_timeout = std::chrono::seconds(20),
                 std::vector<std::string> env = {});
  ~ServiceProcess();
  ServiceProcess(const ServiceProcess&) = delete;
  ServiceProcess& operator=(const ServiceProcess&) = delete;

  [[nodiscard]] const std::string& endpoint() const { return endpoint_; }
  [[nodiscard]] const std::string& name() const { return name_; }
  [[nodiscard]] pid_t pid() const { return pid_; }
  /// True while the child has not exited (reaps it if it has).
  bool alive();
  /// "running", "exited with code N" or "killed by signal N (SIGKILL)".
  std::string describe();
  /// SIGTERM, wait up to `grace`, then SIGKILL; reaps the child. Idempotent.
  void terminate(std::chrono::milliseconds grace = std::chrono::seconds(3));

 private:
  std::string name_;
  std::string endpoint_;
  pid_t pid_ = -1;
  int out_fd_ = -1;
  bool reaped_ = false;
  int wait_status_ = 0;
};

/// Directory of the running executable (/proc/self/exe), for finding the
/// service executables installed next to the orchestrator.
std::string executable_dir();

}  // namespace sadr::orchestrator
