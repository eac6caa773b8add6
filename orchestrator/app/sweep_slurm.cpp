// SPDX-License-Identifier: MIT
// The Slurm executor of `sadr sweep`: one job array per round (array index =
// run index), a dependent aggregation job, squeue polling (sacct may be
// unavailable), failed runs resubmitted up to the sweep's retries.
#include <cstdio>
#include <memory>
#include <thread>

#include "commands.hpp"
#include "sadr/orchestrator/atomic_file.hpp"
#include "sweep_executors.hpp"

namespace sadr::orchestrator {
namespace fs = std::filesystem;
namespace {

std::string quote(const std::string& s) {
  std::string q(1, '\'');
  for (char c : s) {
    if (c == '\'') {
      q.append("'\\''");
    } else {
      q.push_back(c);
    }
  }
  q.push_back('\'');
  return q;
}

/// Runs a shell command and returns its stdout (trailing newline removed).
/// @throws ServiceError (exit 3) naming the command if it fails.
std::string capture(const std::string& command) {
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen((command + " 2>&1").c_str(), "r"), pclose);
  if (!pipe) throw Error(StatusCode::kUnavailable, std::string("cannot run: ").append(command));
  std::string out;
  char buf[4096];
  for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, pipe.get())) > 0;) out.append(buf, n);
  const int rc = pclose(pipe.release());
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  if (rc != 0) {
    std::string why("slurm executor: '");
    why.append(command).append("' failed (status ").append(std::to_string(rc)).append("): ");
    throw Error(StatusCode::kUnavailable, why.append(out));
  }
  return out;
}

std::string join(const std::vector<std::size_t>& v) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (i > 0) s.push_back(',');
    s.append(std::to_string(v[i]));
  }
  return s;
}

}  // namespace

ExecutorReport run_slurm(SweepManifest& m, const fs::path& dir, std::vector<std::size_t> todo,
                         bool quiet) {
  ExecutorReport report;
  const std::string exe = quote(self_executable());
  const std::string d = quote(fs::absolute(dir).string());
  const ExecutorSpec& e = m.executor;
  for (int round = 0; round <= m.retries && !todo.empty() && !interrupt_requested(); ++round) {
    const fs::path abs = fs::absolute(dir);
    ensure_directory(abs / "runs");  // Slurm opens the task logs there before a task starts
    std::string sbatch("sbatch --parsable --job-name=sadr-sweep --chdir=");
    sbatch.append(d)
        .append(" --output=")
        .append(quote((abs / "runs" / "slurm-%A_%a.log").string()));
    sbatch.append(" --cpus-per-task=").append(std::to_string(e.cpus_per_task));
    if (!e.partition.empty()) sbatch.append(" --partition=").append(quote(e.partition));
    for (const auto& a : e.sbatch_args) sbatch.append(" ").append(quote(a));
    std::string task("export OMP_NUM_THREADS=${SLURM_CPUS_PER_TASK:-1}; exec ");
    task.append(exe).append(" sweep-task ").append(d).append(" -q");
    sbatch.append(" --array=").append(join(todo)).append(" --wrap ").append(quote(task));
    const std::string array = capture(sbatch);
    const std::string job = array.substr(0, array.find(';'));
    std::string aggregate(
        "sbatch --parsable --job-name=sadr-sweep-aggregate --dependency=afterany:");
    aggregate.append(job).append(" --chdir=").append(d).append(" --output=");
    aggregate.append(quote((abs / "slurm-aggregate-%j.log").string()));
    std::string agg_cmd("exec ");
    agg_cmd.append(exe).append(" sweep --resume ").append(d).append(" --aggregate-only -q");
    aggregate.append(" --wrap ").append(quote(agg_cmd));
    const std::string agg_out = capture(aggregate);
    const std::string agg = agg_out.substr(0, agg_out.find(';'));
    report.started += todo.size();
    if (!quiet) {
      std::fprintf(stderr, "sadr: submitted array job %s (%zu runs) and aggregation job %s\n",
                   job.c_str(), todo.size(), agg.c_str());
    }
    for (;;) {
      std::string squeue("squeue -h -o %i -j ");
      squeue.append(job).append(",").append(agg);
      const std::string queued = capture(squeue);
      if (queued.empty()) break;
      if (interrupt_requested()) {
        std::string cancel("scancel --signal=TERM --full ");
        cancel.append(job).append("; scancel ").append(agg).append("; true");
        capture(cancel);
      }
      std::this_thread::sleep_for(std::chrono::duration<double>(e.poll_seconds));
    }
    // The aggregation job wrote sweep.json; take its aggregates, fold every result.
    const nlohmann::json aggregates = SweepManifest::read(dir).aggregates;
    m.aggregates = aggregates;
    m.fold_outcomes(dir);
    todo.clear();
    for (const SweepRun& r : m.runs) {
      if (r.state == RunState::kOk) continue;
      if (r.state == RunState::kPending || r.state == RunState::kRunning) {
        // No result.json at all: the task never started or was cancelled before.
        m.runs[r.index].state = RunState::kFailed;
        std::string why("no result: the array task was cancelled or lost (see runs/slurm-");
        why.append(job).append("_").append(std::to_string(r.index)).append(".log)");
        m.runs[r.index].reason = why;
      }
      todo.push_back(r.index);
    }
    m.write(dir);
  }
  return report;
}

}  // namespace sadr::orchestrator
