// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/service_process.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <thread>

#include "sadr/common/status.hpp"

namespace sadr::orchestrator {

std::string executable_dir() {
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::string(".") : exe.parent_path().string();
}

ServiceProcess::ServiceProcess(std::string executable, std::vector<std::string> args,
                               std::string name, std::chrono::milliseconds startup_timeout,
                               std::vector<std::string> env)
    : name_(std::move(name)) {
  if (access(executable.c_str(), X_OK) != 0) {
    throw Error(StatusCode::kUnavailable, "cannot start " + name_ + ": '" + executable +
                                              "' is not an executable file (" +
                                              std::strerror(errno) + ")");
  }
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) {
    throw Error(StatusCode::kUnavailable, "cannot start " + name_ + ": pipe failed");
  }
  const pid_t parent = getpid();
  // The child's environment, built before fork (the child may only call
  // async-signal-safe functions): ours plus SADR_PARENT_PID, which arms the
  // service's parent-death watchdog (service_main.cpp).
  std::vector<std::string> env_text;
  for (char** e = environ; *e != nullptr; ++e) {
    if (std::strncmp(*e, "SADR_PARENT_PID=", 16) != 0 &&
        std::strncmp(*e, "SADR_RUN_SECRET=", 16) != 0) {
      env_text.emplace_back(*e);
    }
  }
  env_text.push_back("SADR_PARENT_PID=" + std::to_string(parent));
  for (auto& e : env) env_text.push_back(std::move(e));
  std::vector<char*> envp;
  for (auto& e : env_text) envp.push_back(e.data());
  envp.push_back(nullptr);
  std::vector<char*> argv;
  argv.push_back(executable.data());
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_ = fork();
  if (pid_ < 0) {
    close(fds[0]);
    close(fds[1]);
    throw Error(StatusCode::kUnavailable, "cannot start " + name_ + ": fork failed");
  }
  if (pid_ == 0) {
    // Child: stdout -> pipe; die with the parent.
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    setpgid(0, 0);  // own process group: a terminal Ctrl-C reaches only the orchestrator,
                    // which checkpoints and then stops the services itself
    if (getppid() != parent) _exit(127);
    dup2(fds[1], STDOUT_FILENO);
    execve(executable.c_str(), argv.data(), envp.data());
    _exit(127);
  }
  close(fds[1]);
  out_fd_ = fds[0];
  // Read the announcement line.
  std::string line;
  const auto deadline = std::chrono::steady_clock::now() + startup_timeout;
  while (true) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      terminate(std::chrono::milliseconds(500));
      throw Error(StatusCode::kUnavailable, name_ + " did not announce its endpoint within " +
                                                std::to_string(startup_timeout.count()) + " ms");
    }
    pollfd p{out_fd_, POLLIN, 0};
    const int r = poll(&p, 1, static_cast<int>(left.count()));
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) continue;
    char c;
    const ssize_t n = read(out_fd_, &c, 1);
    if (n <= 0) {
      terminate(std::chrono::milliseconds(500));
      throw Error(
          StatusCode::kUnavailable,
          name_ + " (" + executable + ") exited before announcing its endpoint: " + describe());
    }
    if (c == '\n') {
      constexpr std::string_view tag = "SADR_ENDPOINT ";
      if (line.rfind(tag, 0) == 0) {
        endpoint_ = line.substr(tag.size());
        break;
      }
      line.clear();
    } else {
      line.push_back(c);
    }
  }
}

ServiceProcess::~ServiceProcess() {
  terminate();
  if (out_fd_ >= 0) close(out_fd_);
}

bool ServiceProcess::alive() {
  if (pid_ <= 0 || reaped_) return false;
  const pid_t r = waitpid(pid_, &wait_status_, WNOHANG);
  if (r == pid_) reaped_ = true;
  return !reaped_;
}

std::string ServiceProcess::describe() {
  if (alive()) return "running";
  if (pid_ <= 0) return "not started";
  if (WIFEXITED(wait_status_))
    return "exited with code " + std::to_string(WEXITSTATUS(wait_status_));
  if (WIFSIGNALED(wait_status_)) {
    const int sig = WTERMSIG(wait_status_);
    const char* nm = sigabbrev_np(sig);
    return "killed by signal " + std::to_string(sig) + (nm ? std::string(" (SIG") + nm + ")" : "");
  }
  return "stopped";
}

void ServiceProcess::terminate(std::chrono::milliseconds grace) {
  if (!alive()) return;
  kill(pid_, SIGTERM);
  const auto deadline = std::chrono::steady_clock::now() + grace;
  while (std::chrono::steady_clock::now() < deadline) {
    if (!alive()) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  kill(pid_, SIGKILL);
  waitpid(pid_, &wait_status_, 0);
  reaped_ = true;
}

}  // namespace sadr::orchestrator
