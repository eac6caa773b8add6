// SPDX-License-Identifier: MIT
// `sadr sweep SWEEP.yaml` / `sadr sweep --resume DIR`: plan the runs (points x
// realizations, seeds), run those not finished through the executor, then
// aggregate every complete point and print a table of what failed.
// Layout and formats: docs/sweeps.md.
#include <cstdio>
#include <fstream>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "cli.hpp"
#include "commands.hpp"
#include "sadr/orchestrator/atomic_file.hpp"
#include "sadr/orchestrator/hash.hpp"
#include "sadr/orchestrator/scene_loader.hpp"
#include "sadr/orchestrator/sweep_aggregation.hpp"
#include "sadr/orchestrator/sweep_manifest.hpp"
#include "sweep_executors.hpp"
#include "sweep_flows.hpp"

namespace sadr::orchestrator {
namespace fs = std::filesystem;
using nlohmann::json;
namespace {

struct SweepCommandOptions {
  std::string sweep;            ///< the sweep file ("" with --resume)
  std::string resume_dir;       ///< --resume DIR
  bool aggregate_only = false;  ///< only fold results and aggregate
  std::string executor;         ///< --executor local|slurm ("" = the file's)
  int workers = 0;              ///< local workers (0 = the file's, else cores)
  std::string output;           ///< -o: the sweep directory ("" = the file's, else sweeps/STEM)
  bool force = false;           ///< start over in a directory that holds another sweep
  bool quiet = false;           ///< no per-run lines
  bool dry_run = false;         ///< check and list the runs, start nothing
  bool no_flow_replay = false;  ///< every run steps its own fluid
};

/// Loads every point's scene (realization 0's overrides) so that a bad
/// parameter value is reported before anything runs, naming the point.
/// @return each point's scene warnings, in point order.
std::vector<std::vector<std::string>> validate_points(const SweepManifest& m) {
  std::string problems;
  std::vector<std::vector<std::string>> warnings;
  for (const auto& p : m.points) {
    try {
      warnings.push_back(
          load_scene(m.base_scene, m.overrides_of(m.runs.at(p.index * m.realizations))).warnings);
    } catch (const Error& e) {
      problems += "\npoint " + std::to_string(p.index) + ": " + e.what();
    }
  }
  if (!problems.empty()) throw InvalidArgument("the sweep has invalid points:" + problems);
  return warnings;
}

/// `sadr sweep --dry-run`: every point's scene checked (with its warnings), and what would
/// run where; nothing is written or started.
int print_dry_run(SweepManifest& m, const fs::path& dir, bool no_flow_replay) {
  const auto warnings = validate_points(m);
  decide_sweep_flows(m, no_flow_replay);
  std::printf("sweep %s: %zu points x %zu realizations = %zu runs (%s executor), in %s\n",
              m.sweep_file.c_str(), m.points.size(), m.realizations, m.runs.size(),
              m.executor.type.c_str(), dir.string().c_str());
  std::printf("base scene %s, sweep seed %llu\n", m.base_scene.c_str(),
              static_cast<unsigned long long>(m.seed));
  for (const auto& p : m.points) {
    std::string values;
    for (const auto& ov : p.overrides) values += (values.empty() ? "" : ", ") + ov.text();
    const SweepRun& first = m.runs.at(p.index * m.realizations);
    const SweepRun& last = m.runs.at(p.index * m.realizations + m.realizations - 1);
    std::printf("point %zu: %s -> %s .. %s\n", p.index, values.c_str(), first.dir.c_str(),
                last.dir.c_str());
    std::printf("  %s\n", flow_line(m.flows.at(p.index)).c_str());
    for (const auto& w : warnings.at(p.index)) std::printf("  warning: %s\n", w.c_str());
  }
  std::printf("dry run: every point's scene is valid; nothing was written or started\n");
  return kExitOk;
}

int cmd_sweep(const SweepCommandOptions& o) {
  install_signal_handlers();
  fs::path dir;
  SweepManifest m;
  if (!o.resume_dir.empty()) {
    dir = o.resume_dir;
    m = SweepManifest::read(dir);
  } else {
    const SweepSpec spec = load_sweep_spec(o.sweep);
    dir = !o.output.empty()      ? fs::path(o.output)
          : !spec.output.empty() ? fs::path(spec.output)
                                 : fs::path("sweeps") / fs::path(o.sweep).stem();
    const std::uint64_t seed = spec.seed ? *spec.seed : load_scene(spec.base_scene).seed;
    SweepManifest fresh = SweepManifest::plan(spec, seed);
    if (o.dry_run) return print_dry_run(fresh, dir, o.no_flow_replay);
    if (fs::exists(dir / std::string(kSweepManifestName)) && !o.force) {
      m = SweepManifest::read(dir);
      if (!m.same_runs(fresh)) {
        throw InvalidArgument("'" + dir.string() +
                              "' holds a different sweep (other scene, points, realizations or "
                              "seed); choose another --output, or --force to start over");
      }
      m.executor = fresh.executor;  // how to run may change between invocations
      m.retries = fresh.retries;
      m.keep = fresh.keep;
    } else {
      (void)validate_points(fresh);
      if (o.force) {
        for (const char* sub : {"runs", "points"}) fs::remove_all(dir / sub);
      }
      ensure_directory(dir);
      write_file_atomic(dir / "sweep.yaml", read_file_bytes(o.sweep));
      m = std::move(fresh);
    }
  }
  if (!o.executor.empty()) m.executor.type = o.executor;
  if (o.workers > 0) m.executor.workers = o.workers;
  // Flow replay per point, decided again by each invocation that runs (the Slurm
  // aggregation job keeps the decision its runs read).
  if (!o.aggregate_only || m.flows.empty()) {
    decide_sweep_flows(m, o.no_flow_replay);
    if (!o.quiet && !o.aggregate_only) {
      for (const auto& p : m.points) {
        std::fprintf(stderr, "sadr: point %zu: %s\n", p.index, flow_line(m.flows[p.index]).c_str());
      }
    }
  }
  m.fold_outcomes(dir);
  m.write(dir);
  std::size_t skipped = 0;
  std::vector<std::size_t> todo;
  for (const SweepRun& r : m.runs) {
    if (r.state == RunState::kOk) {
      ++skipped;
    } else {
      todo.push_back(r.index);
    }
  }
  if (!o.aggregate_only) {
    if (!o.quiet) {
      std::fprintf(
          stderr,
          "sadr: sweep %s: %zu points x %zu realizations; %zu finished, %zu to run (%s executor)\n",
          dir.string().c_str(), m.points.size(), m.realizations, skipped, todo.size(),
          m.executor.type.c_str());
    }
    ExecutorReport rep;
    if (!todo.empty()) {
      rep = m.executor.type == "slurm" ? run_slurm(m, dir, todo, o.quiet)
                                       : run_local(m, dir, todo, m.executor.workers, o.quiet);
    }
    std::fprintf(stderr, "sadr: executed %zu runs, skipped %zu finished\n", rep.started, skipped);
  }
  m.fold_outcomes(dir);
  aggregate_sweep(m, dir, o.quiet);
  if (m.keep == KeepPolicy::kAggregates) (void)remove_finished_flows(m, dir);
  m.write(dir);
  const std::size_t failed = print_sweep_failures(m);
  if (failed > 0) {
    std::fprintf(stderr,
                 "sadr: %zu of %zu runs not finished; run again (sadr sweep --resume %s) "
                 "to resume or retry them\n",
                 failed, m.runs.size(), dir.string().c_str());
    return interrupt_requested() ? kExitInterrupted : kExitServiceFailure;
  }
  bool refused = false;
  for (const auto& [point, a] : m.aggregates.items()) {
    const std::string state = a.value("state", "");
    if (state != "refused" && state != "failed") continue;
    refused = true;
    const std::string note =
        a.contains("notes") && !a["notes"].empty() ? a["notes"][0].get<std::string>() : "";
    std::fprintf(stderr, "sadr: point %s not aggregated (%s): %s\n", point.c_str(), state.c_str(),
                 note.c_str());
  }
  if (refused) return kExitInvalidInput;
  std::fprintf(stderr, "sadr: sweep done: %zu runs; aggregates in %s/points, observables in %s\n",
               m.runs.size(), dir.string().c_str(), (dir / "observables.csv").string().c_str());
  return kExitOk;
}

}  // namespace

Subcommand add_sweep_command(CLI::App& app) {
  auto o = std::make_shared<SweepCommandOptions>();
  auto* sweep = app.add_subcommand(
      "sweep",
      "run a parameter sweep (points x realizations, local or Slurm), resumable; "
      "docs/sweeps.md");
  sweep->add_option("sweep", o->sweep, "sweep file (YAML)")->check(CLI::ExistingFile);
  sweep->add_option("--resume", o->resume_dir, "continue the sweep in this directory")
      ->check(CLI::ExistingDirectory);
  sweep->add_flag("--aggregate-only", o->aggregate_only,
                  "only read the runs' results and aggregate (the Slurm aggregation job)");
  sweep->add_option("--executor", o->executor, "local or slurm (default: the sweep file's)")
      ->check(CLI::IsMember({"local", "slurm"}));
  sweep->add_option("--workers", o->workers, "local executor: runs at once (default: cores)")
      ->check(CLI::Range(1, 4096));
  sweep->add_option("-o,--output", o->output,
                    "sweep directory (default: the file's output, else "
                    "sweeps/<file stem>)");
  sweep->add_flag("--force", o->force, "start over in a directory that holds another sweep");
  sweep->add_flag("-q,--quiet", o->quiet, "no per-run lines");
  sweep->add_flag("--no-flow-replay", o->no_flow_replay,
                  "every run steps its own fluid (default: runs whose fluid is the same, "
                  "deterministic and not reading the SSA compute it once and replay it; "
                  "docs/sweeps.md)");
  sweep->add_flag("--dry-run", o->dry_run,
                  "check every point's scene and list the runs and their folders; write and "
                  "start nothing");
  return {sweep, [o] {
            apply_log_level(o->quiet, "info");
            if (o->sweep.empty() == o->resume_dir.empty()) {
              std::fprintf(stderr, "sadr sweep: give either SWEEP.yaml or --resume DIR\n");
              return static_cast<int>(kExitUsage);
            }
            return cmd_sweep(*o);
          }};
}

}  // namespace sadr::orchestrator
