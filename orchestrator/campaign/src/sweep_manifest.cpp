// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/sweep_manifest.hpp"

#include <cstdio>

#include "sadr/common/rng.hpp"
#include "sadr/common/status.hpp"
#include "sadr/orchestrator/atomic_file.hpp"
#include "sadr/orchestrator/hash.hpp"
#include "sadr/orchestrator/run_manifest.hpp"
#include "sadr/orchestrator/seeds.hpp"

namespace sadr::orchestrator {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {
constexpr std::array<std::string_view, 5> kStates{"pending", "running", "ok", "failed",
                                                  "interrupted"};

RunState parse_state(const std::string& s, const std::string& source) {
  for (std::size_t i = 0; i < kStates.size(); ++i) {
    if (kStates[i] == s) return static_cast<RunState>(i);
  }
  throw InvalidArgument(source + ": unknown run state '" + s + "'");
}
}  // namespace

std::string point_dir(std::size_t point) {
  char name[48];
  std::snprintf(name, sizeof name, "points/p%04zu", point);
  return name;
}

std::string flow_tape_file(const std::string& key) {
  const std::size_t colon = key.find(':');
  return "flows/" + (colon == std::string::npos ? key : key.substr(colon + 1)) + ".bin";
}

std::string_view to_string(RunState state) {
  return kStates.at(static_cast<std::size_t>(state));
}

void write_run_outcome(const fs::path& dir, const RunOutcome& o) {
  const json j{{"state", to_string(o.state)},
               {"exit_code", o.exit_code},
               {"reason", o.reason},
               {"scene_hash", o.scene_hash},
               {"resumed", o.resumed},
               {"attempts", o.attempts},
               {"cpu_s", o.cpu_s},
               {"flow_replay", o.flow_replay},
               {"flow_recorded", o.flow_recorded},
               {"fluid_key", o.fluid_key},
               {"written_utc", utc_now_iso8601()}};
  write_file_atomic(dir / "result.json", j.dump(2) + "\n");
}

std::optional<RunOutcome> read_run_outcome(const fs::path& dir) {
  const fs::path p = dir / "result.json";
  if (!fs::exists(p)) return std::nullopt;
  try {
    const json j = json::parse(read_file_bytes(p));
    RunOutcome o;
    o.state = parse_state(j.at("state").get<std::string>(), p.string());
    o.exit_code = j.at("exit_code").get<int>();
    o.reason = j.at("reason").get<std::string>();
    o.scene_hash = j.at("scene_hash").get<std::string>();
    o.resumed = j.value("resumed", false);
    o.attempts = j.value("attempts", 1);
    o.cpu_s = j.value("cpu_s", -1.0);
    o.flow_replay = j.value("flow_replay", false);
    o.flow_recorded = j.value("flow_recorded", false);
    o.fluid_key = j.value("fluid_key", std::string());
    return o;
  } catch (const std::exception&) {
    return std::nullopt;  // a torn or foreign file: the run is not finished
  }
}

SweepManifest SweepManifest::plan(const SweepSpec& spec, std::uint64_t seed) {
  SweepManifest m;
  m.sweep_file = fs::absolute(spec.source).string();
  m.base_scene = spec.base_scene.string();
  m.seed = seed;
  m.realizations = spec.realizations;
  m.keep = spec.keep;
  m.executor = spec.executor;
  m.retries = spec.retries;
  m.parameters = spec.parameters;
  m.points = spec.points;
  for (std::size_t p = 0; p < m.points.size(); ++p) {
    m.point_seeds.push_back(rng::mix_seed(seed, p));
    for (std::size_t r = 0; r < m.realizations; ++r) {
      SweepRun run;
      run.index = p * m.realizations + r;
      run.point = p;
      run.realization = r;
      run.seed = realization_seed(m.point_seeds.back(), r);
      char name[64];
      std::snprintf(name, sizeof name, "runs/p%04zu_r%04zu", p, r);
      run.dir = name;
      m.runs.push_back(std::move(run));
    }
  }
  return m;
}

std::vector<SceneOverride> SweepManifest::overrides_of(const SweepRun& r) const {
  std::vector<SceneOverride> o = points.at(r.point).overrides;
  o.push_back({"seed", std::to_string(point_seeds.at(r.point))});
  return o;
}

const SweepRun& SweepManifest::run(std::size_t index) const {
  if (index >= runs.size()) {
    throw InvalidArgument("run index " + std::to_string(index) +
                          " is out of range: the sweep has " + std::to_string(runs.size()) +
                          " runs (0.." + std::to_string(runs.size() - 1) + ")");
  }
  return runs[index];
}

void SweepManifest::fold_outcomes(const fs::path& dir) {
  for (std::size_t i = 0; i < runs.size(); ++i) fold_outcome(dir, i);
}

void SweepManifest::fold_outcome(const fs::path& dir, std::size_t index) {
  SweepRun& r = runs.at(index);
  const auto o = read_run_outcome(dir / r.dir);
  if (!o) return;
  r.state = o->state;
  r.exit_code = o->exit_code;
  r.reason = o->reason;
  r.attempts = o->attempts;
  r.scene_hash = o->scene_hash;
  if (r.state == RunState::kRunning) {
    r.state = RunState::kInterrupted;
    r.reason = "the worker ended without a result (killed, cancelled or out of time)";
  }
}

bool SweepManifest::same_runs(const SweepManifest& other) const {
  if (base_scene != other.base_scene || seed != other.seed || realizations != other.realizations ||
      parameters != other.parameters || points.size() != other.points.size()) {
    return false;
  }
  for (std::size_t p = 0; p < points.size(); ++p) {
    if (points[p].overrides != other.points[p].overrides) return false;
  }
  return true;
}

json SweepManifest::to_json() const {
  json pts = json::array();
  for (const auto& p : points) {
    json values = json::object();
    json texts = json::array();
    for (const auto& o : p.overrides) {
      values[o.path] = o.value;
      texts.push_back(o.text());
    }
    pts.push_back({{"index", p.index},
                   {"values", values},
                   {"overrides", texts},
                   {"seed", point_seeds.at(p.index)},
                   {"aggregate_dir", point_dir(p.index)}});
    if (p.index < flows.size()) {
      const PointFlow& f = flows[p.index];
      pts.back()["flow_replay"] = {
          {"on", f.replay}, {"fluid_key", f.fluid_key}, {"reason", f.reason}};
    }
  }
  json rs = json::array();
  for (const auto& r : runs) {
    rs.push_back({{"index", r.index},
                  {"point", r.point},
                  {"realization", r.realization},
                  {"seed", r.seed},
                  {"dir", r.dir},
                  {"state", to_string(r.state)},
                  {"exit_code", r.exit_code},
                  {"reason", r.reason},
                  {"attempts", r.attempts},
                  {"scene_hash", r.scene_hash},
                  {"kept", r.kept}});
  }
  return {{"format", "sadr-sweep"},
          {"format_version", 1},
          {"sweep_file", sweep_file},
          {"base_scene", base_scene},
          {"seed", seed},
          {"realizations", realizations},
          {"keep", to_string(keep)},
          {"executor",
           {{"type", executor.type},
            {"workers", executor.workers},
            {"cpus_per_task", executor.cpus_per_task},
            {"partition", executor.partition},
            {"sbatch_args", executor.sbatch_args},
            {"poll_seconds", executor.poll_seconds}}},
          {"retries", retries},
          {"parameters", parameters},
          {"points", pts},
          {"runs", rs},
          {"aggregates", aggregates}};
}

SweepManifest SweepManifest::from_json(const json& j, const std::string& source) {
  try {
    if (j.at("format") != "sadr-sweep" || j.at("format_version") != 1) {
      throw InvalidArgument(source + ": not a sadr-sweep manifest of format_version 1");
    }
    SweepManifest m;
    m.sweep_file = j.at("sweep_file").get<std::string>();
    m.base_scene = j.at("base_scene").get<std::string>();
    m.seed = j.at("seed").get<std::uint64_t>();
    m.realizations = j.at("realizations").get<std::size_t>();
    m.keep = j.at("keep") == "all" ? KeepPolicy::kAll : KeepPolicy::kAggregates;
    const json& e = j.at("executor");
    m.executor.type = e.at("type").get<std::string>();
    m.executor.workers = e.at("workers").get<int>();
    m.executor.cpus_per_task = e.at("cpus_per_task").get<int>();
    m.executor.partition = e.at("partition").get<std::string>();
    m.executor.sbatch_args = e.at("sbatch_args").get<std::vector<std::string>>();
    m.executor.poll_seconds = e.at("poll_seconds").get<double>();
    m.retries = j.at("retries").get<int>();
    m.parameters = j.at("parameters").get<std::vector<std::string>>();
    for (const auto& p : j.at("points")) {
      SweepPoint sp{p.at("index").get<std::size_t>(), {}};
      for (const auto& t : p.at("overrides"))
        sp.overrides.push_back(parse_override(t.get<std::string>()));
      m.points.push_back(std::move(sp));
      m.point_seeds.push_back(p.at("seed").get<std::uint64_t>());
      if (const auto f = p.find("flow_replay"); f != p.end()) {
        m.flows.push_back({f->at("on").get<bool>(), f->at("fluid_key").get<std::string>(),
                           f->at("reason").get<std::string>()});
      }
    }
    for (const auto& r : j.at("runs")) {
      SweepRun run;
      run.index = r.at("index").get<std::size_t>();
      run.point = r.at("point").get<std::size_t>();
      run.realization = r.at("realization").get<std::size_t>();
      run.seed = r.at("seed").get<std::uint64_t>();
      run.dir = r.at("dir").get<std::string>();
      run.state = parse_state(r.at("state").get<std::string>(), source);
      run.exit_code = r.at("exit_code").get<int>();
      run.reason = r.at("reason").get<std::string>();
      run.attempts = r.at("attempts").get<int>();
      run.scene_hash = r.at("scene_hash").get<std::string>();
      run.kept = r.at("kept").get<std::string>();
      if (run.point >= m.points.size() || run.index != m.runs.size()) {
        throw InvalidArgument(source + ": run " + std::to_string(m.runs.size()) +
                              " has an inconsistent index or point");
      }
      m.runs.push_back(std::move(run));
    }
    m.aggregates = j.value("aggregates", json::object());
    if (m.flows.size() != m.points.size()) m.flows.clear();  // all points, or none decided
    return m;
  } catch (const json::exception& e) {
    throw InvalidArgument(source + ": malformed sweep manifest: " + e.what());
  }
}

void SweepManifest::write(const fs::path& dir) const {
  write_file_atomic(dir / std::string(kSweepManifestName), to_json().dump(1) + "\n");
}

SweepManifest SweepManifest::read(const fs::path& dir) {
  const fs::path p = dir / std::string(kSweepManifestName);
  if (!fs::exists(p)) {
    throw InvalidArgument("'" + dir.string() + "' is not a sweep directory (no " +
                          std::string(kSweepManifestName) + ")");
  }
  json j;
  try {
    j = json::parse(read_file_bytes(p));
  } catch (const json::exception& e) {
    throw InvalidArgument(p.string() + ": not valid JSON: " + e.what());
  }
  return from_json(j, p.string());
}

}  // namespace sadr::orchestrator
