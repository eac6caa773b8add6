// SPDX-License-Identifier: MIT
#include "commands.hpp"
#include "graph_report.hpp"

#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <optional>
#include <thread>

#include "sadr/common/log.hpp"
#include "sadr/fluid/fluid_service.hpp"
#include "sadr/orchestrator/atomic_file.hpp"
#include "sadr/orchestrator/diagnostics.hpp"
#include "sadr/orchestrator/ensemble_accumulator.hpp"
#include "sadr/orchestrator/run_manifest.hpp"
#include "sadr/orchestrator/scene_loader.hpp"
#include "sadr/orchestrator/scene_messages.hpp"
#include "sadr/orchestrator/seeds.hpp"
#include "sadr/orchestrator/service_clients.hpp"
#include "sadr/orchestrator/work_estimate.hpp"

namespace sadr::orchestrator {
namespace fs = std::filesystem;
namespace {

std::atomic<bool> g_interrupt{false};
extern "C" void on_signal(int) {
  g_interrupt.store(true);
}

}  // namespace

void install_signal_handlers() {
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  std::signal(SIGPIPE, SIG_IGN);
  // Before starting anything: what runs killed with -9 left behind.
  if (const std::size_t n = remove_traces_of_dead_runs(); n > 0) {
    log::info("removed ", n, " segment(s) or socket directorie(s) of runs that no longer exist");
  }
}

bool interrupt_requested() {
  return g_interrupt.load();
}

namespace {

bool is_service_failure(const Error& e) {
  return e.code() == StatusCode::kUnavailable || e.code() == StatusCode::kDeadlineExceeded;
}

}  // namespace

void print_plan(const Scene& scene, const Plan& plan, const CliOptions& o) {
  for (const auto& w : scene.warnings) log::warn(w);
  const GraphReport graph = graph_report(scene, plan);  // SSA graph diagnostics
  if (!graph.warning.empty()) log::warn(scene.name, ": ", graph.warning);
  if (o.quiet) return;
  std::fprintf(stderr, "sadr: scene '%s' (%zu particles, %zu species, %zu reactions), t_end = %g\n",
               scene.name.c_str(), scene.particles.size(), scene.species.size(),
               scene.reactions.size(), scene.time.end);
  try {  // the scene's meaning, whatever file it came from (scene_messages.hpp)
    std::fprintf(stderr, "sadr: scene meaning %s\n", scene_meaning_hash(scene, plan).c_str());
  } catch (const std::exception&) {
    // a scene the services refuse: the run says why, where it builds the same messages
  }
  std::fprintf(stderr, "sadr: plan (services as %s):\n", std::string(to_string(o.mode)).c_str());
  for (const auto& line : plan.lines()) std::fprintf(stderr, "  - %s\n", line.c_str());
  for (const auto& line : graph.lines) std::fprintf(stderr, "  - %s\n", line.c_str());
}

namespace {

/// The fluid backend's sub-steps ahead at t = 0, from the backend itself: a fluid_service
/// handler in this process takes the run's Init message (before any service is started, so
/// that validate and the plan of run/resume can print it). Nothing if the plan does not step
/// the fluid, or if the backend refuses the initial state (the run then fails at the service's
/// init with the service's message, as without this).
std::optional<FluidSubsteps> fluid_substeps_at_t0(const Scene& scene, const Plan& plan) {
  if (!plan.fluid_service || !plan.fluid_stepping) return std::nullopt;
  struct QuietLog {  // the handler's own lines are the service's, printed when it runs
    log::Level saved = log::level();
    QuietLog() { log::set_level(log::Level::kError); }
    ~QuietLog() { log::set_level(saved); }
  } quiet;
  fluid::v1::FluidRequest request;
  try {
    *request.mutable_init() = make_fluid_init(scene, plan, realization_seed(scene.seed, 0));
  } catch (const std::exception&) {
    return std::nullopt;  // the run says why, where it builds the same message
  }
  std::string bytes;
  // On a thread of its own, as the embedded service runs: the handler sets that thread's
  // OpenMP thread count (SADR_FLUID_THREADS), not this one's.
  std::thread([&] {
    try {
      fluid::FluidServiceHandler handler;
      bool shutdown = false;
      bytes = handler.handle(request.SerializeAsString(), shutdown);
    } catch (const std::exception&) {
      bytes.clear();
    }
  }).join();
  fluid::v1::FluidReply reply;
  if (!reply.ParseFromString(bytes) || !wire::from_proto(reply.status()).ok()) return std::nullopt;
  return fluid_substeps(reply.init());
}

/// estimate_work() with the backend's sub-steps at t = 0 once the hard limits (memory, disk)
/// allow initialising the backend here and that init fits (in_process_init_fits: otherwise the
/// figure is not computed, and the plan says so).
WorkEstimate estimate_with_backend(const Scene& scene, const Plan& plan, const fs::path& out,
                                   int realizations, int jobs) {
  const MachineLimits machine = machine_limits(out);
  WorkEstimate e = estimate_work(scene, plan, machine, realizations, jobs);
  if (!e.hard.empty()) return e;
  if (!plan.fluid_service || !plan.fluid_stepping) return e;
  const double need = in_process_init_bytes(e, jobs);
  if (!in_process_init_fits(need, machine)) {
    e.substeps_skipped = need;
    return e;
  }
  if (const auto fluid = fluid_substeps_at_t0(scene, plan)) {
    e = estimate_work(scene, plan, machine, realizations, jobs, &*fluid);
  }
  return e;
}

/// The work estimate, printed with the plan, then its limits: hard ones always
/// refuse; soft ones refuse unless --allow-large (then they are warnings).
void check_work(const Scene& scene, const Plan& plan, const CliOptions& o, const fs::path& out,
                int realizations, int jobs) {
  const WorkEstimate e = estimate_with_backend(scene, plan, out, realizations, jobs);
  if (!o.quiet) {
    for (const auto& line : e.lines()) std::fprintf(stderr, "  - %s\n", line.c_str());
  }
  enforce_limits(e, o.allow_large);
  for (const auto& line : e.soft) log::warn(line, " (allowed by --allow-large)");
  for (const auto& note : e.notes) log::warn(note);
}

/// OpenMP threads the fluid will use: --fluid-threads, else OMP_NUM_THREADS (its
/// first value), else every hardware thread (OpenMP's default).
int fluid_threads(const CliOptions& o, unsigned hardware_threads) {
  if (o.fluid_threads > 0) return o.fluid_threads;
  if (const char* v = std::getenv("SADR_FLUID_THREADS"); v && std::atoi(v) > 0) return std::atoi(v);
  if (const char* v = std::getenv("OMP_NUM_THREADS"); v && std::atoi(v) > 0) return std::atoi(v);
  return static_cast<int>(hardware_threads);
}

/// Per-service thread counts for the services launched here (child processes
/// inherit the environment; embedded handlers read it in this process), then
/// the overlap decision of the plan.
void configure_threads_and_overlap(Plan& plan, const CliOptions& o, int jobs) {
  if (o.fluid_threads > 0) setenv("SADR_FLUID_THREADS", std::to_string(o.fluid_threads).c_str(), 1);
  if (o.ssa_threads > 0) setenv("SADR_SSA_THREADS", std::to_string(o.ssa_threads).c_str(), 1);
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  decide_overlap(plan, o.overlap, hw, fluid_threads(o, hw), jobs);
}

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

/// --stop-at T: finite (the parser checks >= 0) and before the scene's end.
void check_stop_at(const CliOptions& o, const Scene& scene, double from) {
  if (o.stop_at < 0) return;
  if (!(o.stop_at > from) || !(o.stop_at <= scene.time.end)) {
    throw InvalidArgument("--stop-at " + format_number(o.stop_at) +
                          " is out of range; allowed: " + format_number(from) +
                          " < T <= " + format_number(scene.time.end) + " (the scene's time.end)");
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
  }
  ensure_directory(dir);
}

}  // namespace

RunResult run_realization(const Scene& scene, const Plan& plan, const CliOptions& o,
                          std::uint64_t realization, const fs::path& out,
                          const LoadedCheckpoint* resume, const RunOptions& base) {
  std::optional<LoadedCheckpoint> reloaded;
  for (int attempt = 0;; ++attempt) {
    ServiceSet services(o.mode, plan, o.remote, std::to_string(realization));
    RunOptions ro = base;
    ro.output_dir = out;
    ro.realization = realization;
    ro.mode = std::string(to_string(o.mode));
    // Services launched here share this host: geometry through shared memory.
    ro.shared_geometry = o.mode != ServiceMode::kRemote && o.shared_geometry;
    ro.timeout = std::chrono::milliseconds(static_cast<long>(o.timeout_s * 1000));
    ro.interrupt = &g_interrupt;
    ro.liveness = [&services] { services.check_alive(); };
    ro.resume = reloaded ? &*reloaded : resume;
    if (o.stop_at >= 0) ro.stop_at = o.stop_at;
    try {
      return run_coupled(scene, plan, services.endpoints(), ro);
    } catch (const Error& e) {
      if (!is_service_failure(e) || attempt >= o.restarts || o.mode == ServiceMode::kRemote) throw;
      const fs::path cp = out / "checkpoint" / std::string(kCheckpointManifestName);
      log::warn("realization ", realization, ": ", e.what(), "; restarting the services (",
                attempt + 1, " of ", o.restarts, ")",
                fs::exists(cp) ? " from the last checkpoint" : " from t = 0 (no checkpoint yet)");
      if (fs::exists(cp)) {
        reloaded = load_checkpoint(cp, scene.source_hash);
      } else {
        reloaded.reset();
      }
    }
  }
}

int report_failure(const std::exception& e) {
  std::fprintf(stderr, "sadr: error: %s\n", e.what());
  return exit_code_of(e);
}

int exit_code_of(const std::exception& e) {
  if (dynamic_cast<const IoError*>(&e)) return kExitIoFailure;
  if (const auto* err = dynamic_cast<const Error*>(&e)) {
    switch (err->code()) {
      case StatusCode::kInvalidArgument:
      case StatusCode::kNotFound:
      case StatusCode::kFailedPrecondition:
        return kExitInvalidInput;
      case StatusCode::kNumericalFailure:
      case StatusCode::kOutOfRange:
        return kExitNumericalFailure;
      case StatusCode::kAborted:
        return kExitInterrupted;
      default:
        return kExitServiceFailure;
    }
  }
  return kExitServiceFailure;
}

int cmd_validate(const CliOptions& o) {
  try {
    const Scene scene = load_scene(o.scene, parse_overrides(o.overrides));
    if (o.strict && !scene.warnings.empty()) {
      for (const auto& w : scene.warnings) log::warn(w);
      std::fprintf(stderr, "%s: refused by --strict: %zu warning(s)\n", o.scene.c_str(),
                   scene.warnings.size());
      return kExitInvalidInput;
    }
    Plan plan = make_plan(scene);
    const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
    decide_overlap(plan, o.overlap, hw, fluid_threads(o, hw), 1);
    print_plan(scene, plan, o);
    const fs::path out =
        scene.output.directory.empty() ? fs::path(".") : fs::path(scene.output.directory);
    const WorkEstimate e = estimate_with_backend(scene, plan, out, 1, 1);
    for (const auto& line : e.lines()) std::fprintf(stderr, "  - %s\n", line.c_str());
    for (const auto& note : e.notes) log::warn(note);
    enforce_limits(e, true);
    for (const auto& line : e.soft) {
      std::fprintf(stderr, "%s: warning: %s; sadr run refuses it without --allow-large\n",
                   o.scene.c_str(), line.c_str());
    }
    std::printf("%s: valid\n", o.scene.c_str());
    return kExitOk;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return kExitInvalidInput;
  }
}

int cmd_run(const CliOptions& o) {
  install_signal_handlers();
  const Scene scene = load_scene(o.scene, parse_overrides(o.overrides));
  Plan plan = make_plan(scene);
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const int r_count = std::max(1, o.realizations);
  const int jobs = o.realization.empty() && r_count > 1
                       ? std::min(r_count, o.jobs > 0 ? o.jobs : static_cast<int>(cores))
                       : 1;
  if (jobs > 1) setenv("OMP_NUM_THREADS", "1", 0);  // one core per realization
  configure_threads_and_overlap(plan, o, jobs);
  print_plan(scene, plan, o);
  check_stop_at(o, scene, 0.0);
  if (!o.realization.empty() && o.output.empty()) {
    throw InvalidArgument("--realization needs --output DIR (the folder shared by all tasks)");
  }
  const unsigned long long task = o.realization.empty() ? 0 : realization_index(o.realization);
  const fs::path out = o.output.empty() ? default_output(scene) : fs::path(o.output);
  check_work(scene, plan, o, out, o.realization.empty() ? r_count : 1, jobs);
  if (o.realization.empty()) {
    prepare_output(out, o.force);
  } else {
    require_directory_or_absent(out);
    ensure_directory(out);  // shared by the array tasks; each writes only its realization
  }
  if (!o.quiet) std::fprintf(stderr, "sadr: writing to %s\n", out.string().c_str());

  if (!o.realization.empty()) {
    // One realization of an ensemble (a cluster array task): DIR/realization_NNNN.
    const std::string name = realization_dir_name(task);
    RunOptions base;
    base.progress = !o.quiet && !o.no_progress;
    base.progress_label = name + " ";
    const RunResult res = run_realization(scene, plan, o, task, out / name, nullptr, base);
    if (!res.interrupted) summarize_at_end(out / name, o.quiet);
    return res.interrupted && g_interrupt ? kExitInterrupted : kExitOk;
  }
  if (r_count == 1) {
    RunOptions base;
    base.progress = !o.quiet && !o.no_progress;
    const RunResult r = run_realization(scene, plan, o, 0, out, nullptr, base);
    if (r.interrupted) {
      std::fprintf(stderr, "sadr: stopped at t = %g; resume with: sadr resume %s\n", r.time,
                   r.last_checkpoint ? r.last_checkpoint->string().c_str() : "(no checkpoint)");
      return g_interrupt ? kExitInterrupted : kExitOk;
    }
    summarize_at_end(out, o.quiet);
    return kExitOk;
  }

  // Ensemble: R realizations on `jobs` workers, each with its own services.
  std::vector<std::string> species = scene.output.species;
  EnsembleAccumulator ensemble(species, scene.particles.size());
  // Realizations finish in any order; they are added in index order (a
  // reorder buffer) so the floating-point sums, and the files, are reproducible.
  using Frames = std::map<std::size_t, std::pair<double, std::vector<SpeciesColumn>>>;
  std::map<int, Frames> pending;
  int next_to_add = 0;
  std::mutex mutex;
  std::atomic<int> next{0}, done{0};
  std::vector<FailedRealization> failed;
  auto flush = [&] {  // under `mutex`
    for (auto it = pending.find(next_to_add); it != pending.end();
         it = pending.find(++next_to_add)) {
      for (const auto& [k, f] : it->second) ensemble.add(k, f.first, f.second);
      pending.erase(it);
    }
  };
  const auto t0 = std::chrono::steady_clock::now();
  auto worker = [&] {
    for (int r; (r = next++) < r_count && !g_interrupt;) {
      // Frames of this realization, added to the ensemble once it succeeds.
      Frames frames;
      RunOptions base;
      base.progress = false;
      base.on_frame = [&frames](std::size_t k, double t, std::span<const SpeciesColumn> cols) {
        frames[k] = {t, std::vector<SpeciesColumn>(cols.begin(), cols.end())};
      };
      const std::string name = realization_dir_name(static_cast<std::uint64_t>(r));
      RunResult res;
      // Each attempt starts at t = 0 (the ensemble needs every frame): drop the frames of a
      // failed one.
      auto failure = run_ensemble_member(
          scene, plan, o, r, out / name, false, base, [&frames] { frames.clear(); }, res);
      std::lock_guard lock(mutex);
      if (failure) {
        // Recorded; the other realizations go on (docs/sweeps.md: faults).
        std::fprintf(stderr, "sadr: realization %d failed: %s\n", r, failure->reason.c_str());
        failed.push_back(std::move(*failure));
        pending.emplace(r, Frames{});  // adds nothing; the later ones are added in order
        flush();
        continue;
      }
      if (!res.interrupted) pending.emplace(r, std::move(frames));
      flush();
      const int d = ++done;
      const double el =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (!o.quiet) {
        std::fprintf(stderr, "sadr: realization %d done (%d/%d), elapsed %.1f s, ETA %.1f s\n", r,
                     d, r_count, el, el / d * (r_count - d));
      }
    }
  };
  std::vector<std::thread> pool;
  for (int j = 0; j < jobs; ++j) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  std::sort(failed.begin(), failed.end(),
            [](const auto& x, const auto& y) { return x.realization < y.realization; });
  write_ensemble_manifest(out, scene, r_count, o.retries, failed);
  ensure_directory(out / "ensemble");
  for (std::size_t k = 0; k < ensemble.frame_count(); ++k) {
    if (ensemble.realizations(k) == 0) continue;
    char name[48];
    std::snprintf(name, sizeof name, "ensemble/frame_%06zu.csv", k);
    ensemble.write_csv(k, out / name, scene.particles.ids);
  }
  std::fprintf(stderr, "sadr: %d realizations; ensemble mean/variance in %s\n", done.load(),
               (out / "ensemble").string().c_str());
  if (!failed.empty()) return report_failed_realizations(out, failed);
  if (!g_interrupt) summarize_at_end(out, o.quiet);
  return g_interrupt ? kExitInterrupted : kExitOk;
}

int cmd_resume(const CliOptions& o) {
  install_signal_handlers();
  if (fs::exists(fs::path(o.checkpoint) / "ensemble.json")) return resume_ensemble(o, o.checkpoint);
  // A directory: the checkpoint directory itself, or a run's folder holding checkpoint/.
  fs::path manifest_path = o.checkpoint;
  if (fs::is_directory(manifest_path)) {
    const fs::path here = manifest_path / std::string(kCheckpointManifestName);
    const fs::path in_run = manifest_path / "checkpoint" / std::string(kCheckpointManifestName);
    if (fs::exists(here)) {
      manifest_path = here;
    } else if (fs::exists(in_run)) {
      manifest_path = in_run;
    } else {
      throw InvalidArgument("'" + o.checkpoint + "' holds neither " + here.string() + " nor " +
                            in_run.string() +
                            " (pass a run's folder, its checkpoint directory or its "
                            "checkpoint.json; a run that wrote no checkpoint cannot be resumed)");
    }
  }
  LoadedCheckpoint cp = load_checkpoint(manifest_path, "");
  const fs::path run_dir = manifest_path.parent_path().parent_path();
  // The overrides of the run (run.json) make the same effective scene again.
  const Scene scene =
      load_scene(cp.manifest.scene_path, parse_overrides(read_run_overrides(run_dir)));
  if (scene.source_hash != cp.manifest.scene_hash) {
    throw InvalidArgument("checkpoint '" + o.checkpoint + "' was written for scene '" +
                          cp.manifest.scene_path + "' with hash " + cp.manifest.scene_hash +
                          ", but that file now has hash " + scene.source_hash +
                          " (the scene changed since the run started)");
  }
  check_manifest_fits_scene(cp.manifest, scene.time.end, scene.time.coupling_step,
                            scene.output.times.size(), scene.seed, manifest_path.string());
  Plan plan = make_plan(scene);
  configure_threads_and_overlap(plan, o, 1);
  print_plan(scene, plan, o);
  check_stop_at(o, scene, cp.manifest.time);
  const fs::path out = o.output.empty() ? run_dir : fs::path(o.output);
  check_work(scene, plan, o, out, 1, 1);
  if (!o.quiet)
    std::fprintf(stderr, "sadr: resuming realization %llu at t = %g (step %llu) into %s\n",
                 static_cast<unsigned long long>(cp.manifest.realization), cp.manifest.time,
                 static_cast<unsigned long long>(cp.manifest.step_index), out.string().c_str());
  RunOptions base;
  base.progress = !o.quiet && !o.no_progress;
  const RunResult r = run_realization(scene, plan, o, cp.manifest.realization, out, &cp, base);
  if (!r.interrupted) summarize_at_end(out, o.quiet);
  return r.interrupted && g_interrupt ? kExitInterrupted : kExitOk;
}

}  // namespace sadr::orchestrator
