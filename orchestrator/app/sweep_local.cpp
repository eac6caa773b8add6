// SPDX-License-Identifier: MIT
// The local executor of `sadr sweep`: N worker processes at a time.
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <deque>
#include <map>
#include <thread>

#include "commands.hpp"
#include "sadr/orchestrator/atomic_file.hpp"
#include "sweep_executors.hpp"

namespace sadr::orchestrator {
namespace fs = std::filesystem;

std::string self_executable() {
  return fs::read_symlink("/proc/self/exe").string();
}

namespace {

/// fork + exec `sadr sweep-task DIR --index I -q` in a new process group,
/// stdout and stderr into the run's worker.log.
pid_t spawn_worker(const std::string& exe, const fs::path& dir, const SweepRun& run, int threads) {
  ensure_directory(dir / run.dir);
  const std::string log = (dir / run.dir / "worker.log").string();
  const std::string index = std::to_string(run.index);
  const std::string dir_text = dir.string();
  const std::string omp = std::to_string(threads);
  const pid_t pid = fork();
  if (pid < 0) throw IoError(std::string("fork: ") + std::strerror(errno));
  if (pid == 0) {
    setpgid(0, 0);
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    if (fd >= 0) {
      dup2(fd, 1);
      dup2(fd, 2);
      close(fd);
    }
    setenv("OMP_NUM_THREADS", omp.c_str(), 0);
    execl(exe.c_str(), exe.c_str(), "sweep-task", dir_text.c_str(), "--index", index.c_str(), "-q",
          static_cast<char*>(nullptr));
    _exit(127);
  }
  setpgid(pid, pid);  // also here: no race with the child's own call
  return pid;
}

/// What to record when a worker ended without writing its result.
RunOutcome outcome_of_exit(int status, int attempts) {
  RunOutcome o;
  o.attempts = attempts;
  if (WIFSIGNALED(status)) {
    o.state = RunState::kFailed;
    o.exit_code = 128 + WTERMSIG(status);
    o.reason = std::string("worker killed by signal ") + std::to_string(WTERMSIG(status)) + " (" +
               strsignal(WTERMSIG(status)) + ")";
  } else {
    o.state = RunState::kFailed;
    o.exit_code = WEXITSTATUS(status);
    o.reason = "worker exited with code " + std::to_string(o.exit_code) + " without a result";
  }
  return o;
}

}  // namespace

ExecutorReport run_local(SweepManifest& m, const fs::path& dir, std::vector<std::size_t> todo,
                         int workers, bool quiet) {
  ExecutorReport report;
  const std::string exe = self_executable();
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (workers <= 0) workers = cores;
  const int threads = std::max(1, cores / workers);
  std::deque<std::size_t> queue(todo.begin(), todo.end());
  std::map<std::size_t, int> tries;  // this invocation
  std::map<pid_t, std::size_t> running;
  bool forwarded = false;
  while (!queue.empty() || !running.empty()) {
    while (!interrupt_requested() && !queue.empty() && static_cast<int>(running.size()) < workers) {
      const std::size_t i = queue.front();
      queue.pop_front();
      m.runs[i].state = RunState::kRunning;
      running[spawn_worker(exe, dir, m.runs[i], threads)] = i;
      ++tries[i];
      ++report.started;
    }
    if (interrupt_requested() && !forwarded) {
      for (const auto& [pid, i] : running) kill(-pid, SIGTERM);  // they checkpoint and stop
      forwarded = true;
      queue.clear();
    }
    if (running.empty()) break;
    int status = 0;
    const pid_t pid = waitpid(-1, &status, WNOHANG);
    if (pid <= 0) {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      continue;
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;  // not a worker (a service of ours is not a child)
    const std::size_t i = it->second;
    running.erase(it);
    const fs::path rd = dir / m.runs[i].dir;
    auto o = read_run_outcome(rd);
    if (!o || o->state == RunState::kRunning) {
      const RunOutcome synth = outcome_of_exit(status, o ? o->attempts : m.runs[i].attempts + 1);
      RunOutcome keep = synth;
      if (o) keep.scene_hash = o->scene_hash;
      write_run_outcome(rd, keep);
    }
    m.fold_outcome(dir, i);
    const SweepRun& r = m.runs[i];
    if (!quiet) {
      std::fprintf(stderr, "sadr: run %zu (%s) %s%s%s\n", r.index, r.dir.c_str(),
                   std::string(to_string(r.state)).c_str(), r.reason.empty() ? "" : ": ",
                   r.reason.substr(0, r.reason.find('\n')).c_str());
    }
    if (r.state == RunState::kFailed && tries[i] <= m.retries && !interrupt_requested()) {
      queue.push_back(i);
    }
    m.write(dir);
  }
  return report;
}

}  // namespace sadr::orchestrator
