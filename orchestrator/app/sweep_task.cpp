// SPDX-License-Identifier: MIT
// `sadr sweep-task DIR [--index I]`: one run of a sweep, the same command for
// every executor. The index comes from --index, SLURM_ARRAY_TASK_ID or
// JOB_COMPLETION_INDEX (Kubernetes Indexed Job). The run's scene is the base
// scene with its point's overrides and `seed` = the point seed; it resumes
// from its checkpoint when one is there. When its point replays the flow
// (sweep_flows.hpp) it replays SWEEP_DIR/flows/<key>.bin, recording it first
// when no other run has. It writes only its own directory (and that file),
// ending with result.json (state, exit code, reason, CPU seconds, flow replay).
#include <sys/resource.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>

#include "cli.hpp"
#include "commands.hpp"
#include "sadr/common/log.hpp"
#include "sadr/orchestrator/atomic_file.hpp"
#include "sadr/orchestrator/scene_loader.hpp"
#include "sadr/orchestrator/scene_messages.hpp"
#include "sadr/orchestrator/sweep_manifest.hpp"
#include "sweep_flows.hpp"

namespace sadr::orchestrator {
namespace fs = std::filesystem;
namespace {

struct SweepTaskOptions {
  std::string directory;   ///< the sweep directory
  std::string index;       ///< --index ("" = from the environment)
  ServiceOptions service;  ///< defaults but -q
};

std::size_t task_index(const SweepTaskOptions& o) {
  std::string text = o.index;
  const char* from = "--index";
  for (const char* var : {"SLURM_ARRAY_TASK_ID", "JOB_COMPLETION_INDEX"}) {
    if (!text.empty()) break;
    if (const char* v = std::getenv(var)) {
      text = v;
      from = var;
    }
  }
  if (text.empty()) {
    throw InvalidArgument(
        "sweep-task: no run index (pass --index I, or set SLURM_ARRAY_TASK_ID or "
        "JOB_COMPLETION_INDEX)");
  }
  char* end = nullptr;
  const unsigned long long i = std::strtoull(text.c_str(), &end, 10);
  if (*end != '\0' || text[0] == '-') {
    throw InvalidArgument(std::string("sweep-task: ") + from + " '" + text +
                          "' is not a run index (a whole number >= 0)");
  }
  return static_cast<std::size_t>(i);
}

/// User + sys CPU seconds of this process and of the children it reaped (the services).
double cpu_seconds() {
  double s = 0;
  for (const int who : {RUSAGE_SELF, RUSAGE_CHILDREN}) {
    rusage u{};
    if (getrusage(who, &u) != 0) return -1;
    s += static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
  }
  return s;
}

int cmd_sweep_task(const SweepTaskOptions& c) {
  const ServiceOptions& o = c.service;
  install_signal_handlers();
  const fs::path dir = c.directory;
  const SweepManifest m = SweepManifest::read(dir);
  const SweepRun& run = m.run(task_index(c));
  const fs::path rd = dir / run.dir;
  ensure_directory(rd);
  const auto previous = read_run_outcome(rd);
  if (previous && previous->state == RunState::kOk) {
    std::fprintf(stderr, "sadr: run %zu (%s) already finished; nothing to do\n", run.index,
                 run.dir.c_str());
    return kExitOk;
  }
  RunOutcome out;
  out.state = RunState::kRunning;
  out.attempts = previous ? previous->attempts + 1 : 1;
  write_run_outcome(rd, out);
  try {
    const Scene scene = load_scene(m.base_scene, m.overrides_of(run));
    out.scene_hash = scene.source_hash;
    Plan plan = make_plan(scene);
    const fs::path cp = rd / "checkpoint" / std::string(kCheckpointManifestName);
    std::optional<LoadedCheckpoint> resume;
    if (fs::exists(cp)) {
      resume = load_checkpoint(cp, scene.source_hash);
      out.resumed = true;
      std::fprintf(stderr, "sadr: run %zu resumes at t = %g from its checkpoint\n", run.index,
                   resume->manifest.time);
    } else {
      for (const char* sub : {"frames", "checkpoint"}) fs::remove_all(rd / sub);
    }
    decide_sweep_task_flow(plan, m, run, rd, resume.has_value());
    if (!o.quiet) print_plan(scene, plan, o);
    RunOptions base;
    base.progress = false;
    if (plan.flow_replay) {
      out.fluid_key = fluid_key(scene, plan);
      const SharedFlowTape tape =
          shared_flow_tape(scene, plan, o, dir / flow_tape_file(out.fluid_key));
      out.flow_recorded = tape.recorded;
      if (tape.stopped) {  // nothing ran: resumed (from t = 0) like an interrupted run
        out.state = RunState::kInterrupted;
        out.exit_code = kExitInterrupted;
        out.reason = "interrupted while its flow replay file was recorded or awaited";
        out.cpu_s = cpu_seconds();
        write_run_outcome(rd, out);
        return out.exit_code;
      }
      if (tape.path.empty()) {
        log::warn("run ", run.index, ": ", tape.reason);
        plan.flow_replay = false;
        plan.flow_replay_reason = tape.reason;
        out.fluid_key.clear();
      }
      base.flow_replay = tape.path;
    }
    out.flow_replay = plan.flow_replay;
    const RunResult res =
        run_realization(scene, plan, o, run.realization, rd, resume ? &*resume : nullptr, base);
    out.state = res.interrupted ? RunState::kInterrupted : RunState::kOk;
    out.exit_code = res.interrupted ? kExitInterrupted : kExitOk;
    if (res.interrupted) out.reason = "interrupted at t = " + std::to_string(res.time);
  } catch (const std::exception& e) {
    out.state = RunState::kFailed;
    out.exit_code = report_failure(e);
    out.reason = e.what();
  }
  out.cpu_s = cpu_seconds();
  write_run_outcome(rd, out);
  return out.exit_code;
}

}  // namespace

Subcommand add_sweep_task_command(CLI::App& app) {
  auto o = std::make_shared<SweepTaskOptions>();
  auto* sweep_task =
      app.add_subcommand("sweep-task", "one run of a sweep (the worker command of every executor)");
  sweep_task->add_option("directory", o->directory, "the sweep directory")
      ->required()
      ->check(CLI::ExistingDirectory);
  sweep_task->add_option("--index", o->index,
                         "run index (default: SLURM_ARRAY_TASK_ID, else JOB_COMPLETION_INDEX)");
  sweep_task->add_flag("-q,--quiet", o->service.quiet, "no plan");
  return {sweep_task, [o] {
            apply_log_level(o->service.quiet, "info");
            return cmd_sweep_task(*o);
          }};
}

}  // namespace sadr::orchestrator
