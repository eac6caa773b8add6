// SPDX-License-Identifier: MIT
// `sadr sweep SWEEP.yaml` / `sadr sweep --resume DIR`: plan the runs (points x
// realizations, seeds), run those not finished through the executor, then
// aggregate every complete point and print a table of what failed.
// Layout and formats: docs/sweeps.md.
#include <cstdio>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "commands.hpp"
#include "sadr/orchestrator/atomic_file.hpp"
#include "sadr/orchestrator/hash.hpp"
#include "sadr/orchestrator/scene_loader.hpp"
#include "sadr/orchestrator/sweep_aggregate.hpp"
#include "sadr/orchestrator/sweep_manifest.hpp"
#include "sweep_executors.hpp"

namespace sadr::orchestrator {
namespace fs = std::filesystem;
using nlohmann::json;
namespace {

/// A CSV field: quoted when it holds a comma or a quote.
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

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

/// Aggregates each point whose runs all finished (and that is not aggregated
/// yet), applies the keep policy, and rewrites DIR/observables.csv.
void aggregate(SweepManifest& m, const fs::path& dir, bool quiet) {
  std::string header = "point,realization";
  for (const auto& p : m.parameters) header.append(",").append(csv_field(p));
  header += ",frame,time,species,total\n";
  for (const auto& p : m.points) {
    const std::string key = std::to_string(p.index);
    std::vector<fs::path> runs;
    std::vector<std::string> prefixes;
    std::set<std::string> hashes;
    std::size_t ok = 0;
    for (std::size_t r = 0; r < m.realizations; ++r) {
      const SweepRun& run = m.runs[p.index * m.realizations + r];
      ok += run.state == RunState::kOk;
      hashes.insert(run.scene_hash);
      runs.push_back(dir / run.dir);
      std::string prefix = key + "," + std::to_string(r);
      for (const auto& o : p.overrides) prefix.append(",").append(csv_field(o.value));
      prefixes.push_back(prefix);
    }
    json& a = m.aggregates[key];
    if (a.is_object() && a.value("state", "") == "done" &&
        a.value("realizations", std::size_t{0}) == m.realizations) {
      continue;  // aggregated before (its frames may be gone: keep: aggregates)
    }
    a = {{"dir", point_dir(p.index)}, {"realizations", ok}, {"of", m.realizations}};
    if (ok < m.realizations) {
      a["state"] = "incomplete";
      a["notes"] = json::array({std::to_string(ok) + " of " + std::to_string(m.realizations) +
                                " runs finished; not aggregated"});
      continue;
    }
    if (hashes.size() != 1) {
      a["state"] = "refused";
      a["notes"] = json::array({"the runs of this point ran different effective scenes (" +
                                std::to_string(hashes.size()) +
                                " scene hashes); refusing to aggregate them"});
      continue;
    }
    const fs::path out = dir / point_dir(p.index);
    ensure_directory(out);
    std::ofstream obs(out / "observables.csv.tmp", std::ios::binary);
    obs << header;
    try {
      // The scene's named observables (output.observables), from the scene the runs ran.
      const Scene scene =
          load_scene(m.base_scene, m.overrides_of(m.runs[p.index * m.realizations]));
      if (scene.source_hash != *hashes.begin()) {
        throw InvalidArgument("the scene " + m.base_scene + " changed since its runs ran (hash " +
                              scene.source_hash + ", the runs ran " + *hashes.begin() + ")");
      }
      const PointAggregate pa =
          aggregate_point(runs, prefixes, out, "aggregate", obs, named_observables(scene));
      obs.close();
      fs::rename(out / "observables.csv.tmp", out / "observables.csv");
      a["state"] = "done";
      a["frames"] = pa.frames;
      a["positions_identical"] = pa.positions_identical;
      a["velocity_density_aggregated"] = pa.fluid_columns;
      a["notes"] = pa.notes;
      a["scene_hash"] = *hashes.begin();
    } catch (const Error& e) {
      a["state"] = "failed";
      a["notes"] = json::array({e.what()});
      continue;
    }
    if (m.keep == KeepPolicy::kAggregates) {
      for (std::size_t r = 1; r < m.realizations; ++r) {
        SweepRun& run = m.runs[p.index * m.realizations + r];
        const fs::path rd = dir / run.dir;
        for (const char* sub : {"frames", "checkpoint"}) fs::remove_all(rd / sub);
        for (const auto& f : fs::directory_iterator(rd)) {
          if (f.path().extension() == ".pvd") fs::remove(f.path());
        }
        run.kept = "run.json, result.json, worker.log";
      }
    }
    if (!quiet) {
      std::fprintf(stderr, "sadr: point %zu aggregated over %zu realizations into %s\n", p.index,
                   ok, out.string().c_str());
    }
  }
  // The sweep's tidy observables: every aggregated point's file, one header.
  std::string all = header;
  for (const auto& p : m.points) {
    const fs::path f = dir / point_dir(p.index) / "observables.csv";
    if (!fs::exists(f)) continue;
    const std::string text = read_file_bytes(f);
    all += text.substr(std::min(text.size(), header.size()));
  }
  write_file_atomic(dir / "observables.csv", all);
}

/// Prints every run that did not finish, with its reason; returns how many.
std::size_t print_failures(const SweepManifest& m) {
  std::size_t n = 0;
  for (const SweepRun& r : m.runs) {
    if (r.state == RunState::kOk) continue;
    if (n++ == 0) {
      std::fprintf(stderr, "sadr: runs not finished:\n  %-6s %-5s %-4s %-12s %-4s %-8s %s\n", "run",
                   "point", "real", "state", "exit", "attempts", "reason");
    }
    const std::string reason = r.reason.substr(0, r.reason.find('\n'));
    std::fprintf(stderr, "  %-6zu %-5zu %-4zu %-12s %-4d %-8d %s\n", r.index, r.point,
                 r.realization, std::string(to_string(r.state)).c_str(), r.exit_code, r.attempts,
                 reason.c_str());
  }
  return n;
}

/// `sadr sweep --dry-run`: every point's scene checked (with its warnings), and what would
/// run where; nothing is written or started.
int print_dry_run(const SweepManifest& m, const fs::path& dir) {
  const auto warnings = validate_points(m);
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
    for (const auto& w : warnings.at(p.index)) std::printf("  warning: %s\n", w.c_str());
  }
  std::printf("dry run: every point's scene is valid; nothing was written or started\n");
  return kExitOk;
}

}  // namespace

int cmd_sweep(const CliOptions& o) {
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
    if (o.dry_run) return print_dry_run(fresh, dir);
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
  aggregate(m, dir, o.quiet);
  m.write(dir);
  const std::size_t failed = print_failures(m);
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

}  // namespace sadr::orchestrator
