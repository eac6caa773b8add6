// SPDX-License-Identifier: MIT
// `sadr run SCENE`: one realization, one task of a cluster array
// (--realization K; the tasks share OUTPUT/flow_replay.bin when the fluid is
// deterministic), or an ensemble of R realizations (ensemble_pool.hpp).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <span>
#include <thread>

#include "cli.hpp"
#include "commands.hpp"
#include "sadr/common/log.hpp"
#include "sadr/orchestrator/atomic_file.hpp"
#include "sadr/orchestrator/diagnostics.hpp"
#include "sadr/orchestrator/ensemble_accumulator.hpp"
#include "sadr/orchestrator/ensemble_pool.hpp"
#include "sadr/orchestrator/run_manifest.hpp"
#include "sadr/orchestrator/scene_loader.hpp"
#include "sadr/orchestrator/scene_override.hpp"

namespace sadr::orchestrator {
namespace fs = std::filesystem;
namespace {

struct RunCommandOptions {
  std::string scene;                   ///< scene file
  std::vector<std::string> overrides;  ///< --set PATH=VALUE
  int realizations = 1;
  int jobs = 0;        ///< parallel realizations (0 = number of cores)
  bool force = false;  ///< overwrite a non-empty output directory
  /// Run only this realization (a cluster array task); "" = all. "env" takes
  /// the index from SLURM_ARRAY_TASK_ID or JOB_COMPLETION_INDEX.
  std::string realization;
  ServiceOptions service;
};

fs::path default_output(const Scene& scene) {
  if (!scene.output.directory.empty()) return scene.output.directory;  // relative to the cwd
  std::string stamp = utc_now_iso8601();  // 2026-11-22T03:00:00Z -> 20261122-030000
  std::string compact;
  for (char c : stamp) {
    if (std::isdigit(static_cast<unsigned char>(c))) compact.push_back(c);
    if (c == 'T') compact.push_back('-');
  }
  return fs::path("runs") / (scene.name + "-" + compact);
}

/// Refuses an output path that exists but is not a directory (before anything is written).
void require_directory_or_absent(const fs::path& dir) {
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) {
    throw InvalidArgument("output '" + dir.string() +
                          "' exists and is not a directory; allowed: a directory or a new path "
                          "(--output)");
  }
}

/// The index K of --realization K|env, checked before any folder is created.
unsigned long long realization_index(const std::string& option) {
  std::string index = option;
  if (index == "env") {
    const char* v = std::getenv("SLURM_ARRAY_TASK_ID");
    if (!v) v = std::getenv("JOB_COMPLETION_INDEX");
    if (!v) {
      throw InvalidArgument(
          "--realization env: neither SLURM_ARRAY_TASK_ID nor "
          "JOB_COMPLETION_INDEX is set");
    }
    index = v;
  }
  char* end = nullptr;
  const unsigned long long r = std::strtoull(index.c_str(), &end, 10);
  if (index.empty() || index.size() > 4 || *end != '\0' || index[0] == '-' || index[0] == '+' ||
      r > 9999) {
    throw InvalidArgument("--realization '" + index.substr(0, 32) + "' (allowed: 0..9999 or env)");
  }
  return r;
}

void prepare_output(const fs::path& dir, bool force) {
  require_directory_or_absent(dir);
  if (fs::exists(dir) && !fs::is_empty(dir)) {
    if (!force) {
      throw InvalidArgument("output directory '" + dir.string() +
                            "' exists and is not empty (pass --force to overwrite, or choose "
                            "another with --output)");
    }
    for (const auto& sub : {"frames", "checkpoint", "ensemble"}) fs::remove_all(dir / sub);
    fs::remove(flow_replay_path(dir));  // recorded again: never the answers of an earlier run
  }
  ensure_directory(dir);
}

int cmd_run(const RunCommandOptions& c) {
  const ServiceOptions& o = c.service;
  install_signal_handlers();
  const Scene scene = load_scene(c.scene, parse_overrides(c.overrides));
  Plan plan = make_plan(scene);
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const int r_count = std::max(1, c.realizations);
  const int jobs = c.realization.empty() && r_count > 1
                       ? std::min(r_count, c.jobs > 0 ? c.jobs : static_cast<int>(cores))
                       : 1;
  if (jobs > 1) setenv("OMP_NUM_THREADS", "1", 0);  // one core per realization
  configure_threads_and_overlap(plan, o, jobs);
  decide_flow_replay(plan, o.no_flow_replay, c.realization.empty() ? r_count : 1);
  if (!c.realization.empty() && plan.flow_replay_allowed && !o.no_flow_replay) {
    plan.flow_replay = true;
    plan.flow_replay_reason =
        "array task: the tasks of one output folder share its flow_replay.bin, the first "
        "records it";
  }
  print_plan(scene, plan, o);
  check_stop_at(o, scene, 0.0);
  if (!c.realization.empty() && o.output.empty()) {
    throw InvalidArgument("--realization needs --output DIR (the folder shared by all tasks)");
  }
  const unsigned long long task = c.realization.empty() ? 0 : realization_index(c.realization);
  const fs::path out = o.output.empty() ? default_output(scene) : fs::path(o.output);
  check_work(scene, plan, o, out, c.realization.empty() ? r_count : 1, jobs);
  if (c.realization.empty()) {
    prepare_output(out, c.force);
  } else {
    require_directory_or_absent(out);
    ensure_directory(out);  // shared by the array tasks; each writes only its realization
  }
  if (!o.quiet) std::fprintf(stderr, "sadr: writing to %s\n", out.string().c_str());

  if (!c.realization.empty()) {
    // One realization of an ensemble (a cluster array task): DIR/realization_NNNN.
    const std::string name = realization_dir_name(task);
    RunOptions base;
    base.progress = !o.quiet && !o.no_progress;
    base.progress_label = name + " ";
    if (plan.flow_replay) {
      const SharedFlowTape tape = shared_flow_tape(scene, plan, o, flow_replay_path(out));
      if (tape.stopped) return kExitInterrupted;  // nothing of the realization ran yet
      if (tape.path.empty()) {
        log::warn(tape.reason);
        plan.flow_replay = false;
        plan.flow_replay_reason = tape.reason;
      }
      base.flow_replay = tape.path;
    }
    const RunResult res = run_realization(scene, plan, o, task, out / name, nullptr, base);
    if (!res.interrupted) summarize_at_end(out / name, o.quiet);
    return res.interrupted && interrupt_requested() ? kExitInterrupted : kExitOk;
  }
  if (r_count == 1) {
    RunOptions base;
    base.progress = !o.quiet && !o.no_progress;
    const RunResult r = run_realization(scene, plan, o, 0, out, nullptr, base);
    if (r.interrupted) {
      std::fprintf(stderr, "sadr: stopped at t = %g; resume with: sadr resume %s\n", r.time,
                   r.last_checkpoint ? r.last_checkpoint->string().c_str() : "(no checkpoint)");
      return interrupt_requested() ? kExitInterrupted : kExitOk;
    }
    summarize_at_end(out, o.quiet);
    return kExitOk;
  }

  // Ensemble: R realizations on `jobs` workers, each with its own services; the
  // fluid first, alone, when it is the same in all of them (flow replay).
  fs::path replay;
  if (plan.flow_replay) {
    replay = prepare_flow_replay(scene, plan, o, out);
    if (replay.empty()) {  // stopped during the fluid pass: `sadr resume` starts it again
      EnsembleManifest::of(scene, r_count, o.retries, {}).write(out);
      std::fprintf(stderr, "sadr: stopped; resume with: sadr resume %s\n", out.string().c_str());
      return kExitInterrupted;
    }
  }
  EnsembleAccumulator ensemble(scene.output.species, scene.particles.size());
  const PoolResult pool =
      run_ensemble_pool(ensemble, r_count, jobs, o.quiet, interrupt_flag(), [&](int r) {
        MemberResult m;
        // Frames of this realization, added to the ensemble once it succeeds.
        RunOptions base;
        base.progress = false;
        base.flow_replay = replay;
        base.on_frame = [&m](std::size_t k, double t, std::span<const SpeciesColumn> cols) {
          m.frames[k] = {t, std::vector<SpeciesColumn>(cols.begin(), cols.end())};
        };
        const std::string name = realization_dir_name(static_cast<std::uint64_t>(r));
        RunResult res;
        // Each attempt starts at t = 0 (the ensemble needs every frame): drop the frames of a
        // failed one.
        m.failure = run_ensemble_member(
            scene, plan, o, r, out / name, false, base, [&m] { m.frames.clear(); }, res);
        m.interrupted = !m.failure && res.interrupted;
        return m;
      });
  const std::vector<FailedRealization>& failed = pool.failed;
  EnsembleManifest::of(scene, r_count, o.retries, failed).write(out);
  write_ensemble_frames(ensemble, out, scene.particles.ids);
  std::fprintf(stderr, "sadr: %d realizations; ensemble mean/variance in %s\n", pool.done,
               (out / "ensemble").string().c_str());
  if (!failed.empty()) return report_failed_realizations(out, failed);
  if (!interrupt_requested()) summarize_at_end(out, o.quiet);
  return interrupt_requested() ? kExitInterrupted : kExitOk;
}

}  // namespace

Subcommand add_run_command(CLI::App& app) {
  auto o = std::make_shared<RunCommandOptions>();
  auto* run = app.add_subcommand("run", "run a scene (one realization, or an ensemble)");
  run->add_option("scene", o->scene, "scene file (YAML)")->required()->check(CLI::ExistingFile);
  add_set_option(run, o->overrides);
  run->add_option("-r,--realizations", o->realizations,
                  "independent realizations with seeds derived from the scene seed; each in "
                  "realization_NNNN/, plus per-frame ensemble mean and variance in ensemble/")
      ->check(CLI::Range(1, 10000));
  run->add_option("-j,--jobs", o->jobs, "realizations run at once (default: number of cores)")
      ->check(CLI::Range(0, 10000));
  run->add_flag("--force", o->force, "overwrite a non-empty output directory");
  run->add_option("--realization", o->realization,
                  "run only realization K (0-based) into OUTPUT/realization_K; 'env' takes K "
                  "from SLURM_ARRAY_TASK_ID or JOB_COMPLETION_INDEX (cluster array jobs; "
                  "combine with 'sadr ensemble OUTPUT')");
  add_service_options(run, o->service);
  add_retries_option(run, o->service);
  add_flow_replay_option(run, o->service);
  return {run, [o] {
            if (const int rc = resolve_service_mode(o->service); rc != kExitOk) return rc;
            use_remote_keys(o->service);
            return cmd_run(*o);
          }};
}

}  // namespace sadr::orchestrator
