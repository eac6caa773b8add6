// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/run_manifest.hpp"

#include <cmath>
#include <cstdlib>
#include <ctime>

#include "sadr/common/build_info.hpp"
#include "sadr/common/status.hpp"
#include "sadr/common/version.hpp"
#include "sadr/orchestrator/atomic_file.hpp"
#include "sadr/orchestrator/hash.hpp"

namespace sadr::orchestrator {
namespace {

/// The one spelling of a realization's folder: this prefix and at least 4 digits.
constexpr std::string_view kRealizationPrefix = "realization_";

}  // namespace

std::string realization_dir_name(std::uint64_t r) {
  std::string digits = std::to_string(r);
  if (digits.size() < 4) digits.insert(0, 4 - digits.size(), '0');
  std::string name(kRealizationPrefix);
  name.append(digits);
  return name;
}

bool is_realization_dir_name(std::string_view name) {
  constexpr std::string_view prefix = kRealizationPrefix;
  if (name.size() < prefix.size() + 4 || name.substr(0, prefix.size()) != prefix) return false;
  for (const char c : name.substr(prefix.size())) {
    if (c < '0' || c > '9') return false;
  }
  return true;
}

RunManifest::RunManifest() : sadr_version(kBuildVersion), protocol_version(kProtocolVersion) {
  for (const char* name : {"OMP_NUM_THREADS", "OMP_WAIT_POLICY", "GOMP_SPINCOUNT"}) {
    const char* value = std::getenv(name);
    environment[name] = value ? value : "";
  }
}

nlohmann::json RunManifest::to_json() const {
  nlohmann::json j = {{"format", "sadr-run"},
                      {"format_version", 1},
                      {"scene_path", scene_path},
                      {"scene_hash", scene_hash},
                      {"overrides", overrides},
                      {"scene_seed", scene_seed},
                      {"realization", realization},
                      {"seed", seed},
                      {"sadr_version", sadr_version},
                      {"protocol_version", protocol_version},
                      {"mode", mode},
                      {"environment", environment},
                      {"started_utc", started_utc},
                      {"finished_utc", finished_utc},
                      {"status", status},
                      {"steps", steps},
                      {"overlapped_steps", overlapped_steps},
                      {"fluid_substeps", fluid_substeps},
                      {"fluid_at_t0", fluid_at_t0},
                      {"fluid_smallest_limit", fluid_smallest_limit},
                      {"ssa_events", ssa_events},
                      {"time", time},
                      {"timings_s", timings_s},
                      {"frames", frames},
                      {"plan", plan}};
  if (!body_forces.empty()) j["body_forces"] = body_forces;
  if (ssa_leaped_molecules > 0) j["ssa_leaped_molecules"] = ssa_leaped_molecules;
  if (!step_control.empty()) j["step_control"] = step_control;
  return j;
}

void RunManifest::note_fluid_limit(double dt, const std::string& criterion, double at) {
  if (!(dt > 0) || !std::isfinite(dt)) return;
  const auto it = fluid_smallest_limit.find("stable_time_step");
  if (it != fluid_smallest_limit.end() && !(dt < it->get<double>())) return;
  fluid_smallest_limit = {
      {"stable_time_step", dt}, {"limiting_criterion", criterion}, {"time", at}};
}

void RunManifest::write(const std::filesystem::path& path) const {
  write_file_atomic(path, to_json().dump(2) + "\n");
}

std::vector<std::string> read_run_overrides(const std::filesystem::path& run_dir) {
  const std::filesystem::path path = run_dir / "run.json";
  if (!std::filesystem::exists(path)) return {};
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(read_file_bytes(path));
  } catch (const nlohmann::json::exception& e) {
    throw InvalidArgument(path.string() + ": not valid JSON: " + e.what());
  }
  if (!j.contains("overrides")) return {};
  if (!j["overrides"].is_array()) {
    throw InvalidArgument(path.string() + ": 'overrides' must be a list of PATH=VALUE texts");
  }
  std::vector<std::string> out;
  for (const auto& v : j["overrides"]) {
    if (!v.is_string()) {
      throw InvalidArgument(path.string() + ": 'overrides' must be a list of PATH=VALUE texts");
    }
    out.push_back(v.get<std::string>());
  }
  return out;
}

std::string utc_now_iso8601() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

}  // namespace sadr::orchestrator
