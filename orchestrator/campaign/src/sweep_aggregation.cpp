// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/sweep_aggregation.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <set>
#include <vector>

#include <nlohmann/json.hpp>

#include "sadr/orchestrator/atomic_file.hpp"
#include "sadr/orchestrator/hash.hpp"
#include "sadr/orchestrator/scene_loader.hpp"
#include "sadr/orchestrator/sweep_aggregate.hpp"

namespace sadr::orchestrator {
namespace fs = std::filesystem;
using nlohmann::json;

/// A CSV field: quoted when it holds a comma or a quote.
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

/// Aggregates each point whose runs all finished (and that is not aggregated
/// yet), applies the keep policy, and rewrites DIR/observables.csv.
void aggregate_sweep(SweepManifest& m, const fs::path& dir, bool quiet) {
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
std::size_t print_sweep_failures(const SweepManifest& m) {
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

}  // namespace sadr::orchestrator
