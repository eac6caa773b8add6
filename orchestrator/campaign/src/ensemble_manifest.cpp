// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/ensemble_manifest.hpp"

#include <nlohmann/json.hpp>

#include "sadr/orchestrator/atomic_file.hpp"
#include "sadr/orchestrator/hash.hpp"
#include "sadr/orchestrator/run_manifest.hpp"
#include "sadr/orchestrator/scene.hpp"

namespace sadr::orchestrator {
namespace fs = std::filesystem;

EnsembleManifest EnsembleManifest::of(const Scene& scene, int realizations, int retries,
                                      std::vector<FailedRealization> failed) {
  EnsembleManifest m;
  m.scene_path = fs::absolute(scene.source_path).string();
  m.overrides = scene.overrides;
  m.scene_hash = scene.source_hash;
  m.realizations = realizations;
  m.retries = retries;
  m.failed = std::move(failed);
  return m;
}

void EnsembleManifest::write(const fs::path& dir) const {
  nlohmann::json f = nlohmann::json::array();
  for (const auto& x : failed) {
    f.push_back({{"realization", x.realization},
                 {"exit_code", x.exit_code},
                 {"reason", x.reason},
                 {"attempts", x.attempts}});
  }
  const nlohmann::json j{{"format", "sadr-ensemble"}, {"format_version", 1},
                         {"scene_path", scene_path},  {"overrides", overrides},
                         {"scene_hash", scene_hash},  {"realizations", realizations},
                         {"retries", retries},        {"failed", f}};
  write_file_atomic(dir / kEnsembleManifestName, j.dump(2) + "\n");
}

EnsembleManifest EnsembleManifest::read(const fs::path& dir) {
  const nlohmann::json j = nlohmann::json::parse(read_file_bytes(dir / kEnsembleManifestName));
  EnsembleManifest m;
  // In the order `sadr resume` has always read them (the first missing key is the one named).
  m.overrides = j.at("overrides").get<std::vector<std::string>>();
  m.scene_path = j.at("scene_path").get<std::string>();
  m.scene_hash = j.at("scene_hash").get<std::string>();
  m.realizations = j.at("realizations").get<int>();
  if (j.contains("retries") && j["retries"].is_number_integer())
    m.retries = j["retries"].get<int>();
  if (j.contains("failed") && j["failed"].is_array()) {
    for (const auto& x : j["failed"]) {
      if (!x.is_object()) continue;
      m.failed.push_back({x.value("realization", 0), x.value("exit_code", 0),
                          x.value("reason", std::string()), x.value("attempts", 1)});
    }
  }
  return m;
}

bool is_ensemble_dir(const fs::path& dir) {
  return fs::exists(dir / kEnsembleManifestName);
}

bool realization_finished(const fs::path& rd) {
  return fs::exists(rd / "run.json") &&
         nlohmann::json::parse(read_file_bytes(rd / "run.json")).value("status", "") == "ok";
}

std::vector<int> unfinished_realizations(const fs::path& dir, int count) {
  std::vector<int> out;
  for (int r = 0; r < count; ++r) {
    if (!realization_finished(dir / realization_dir_name(static_cast<std::uint64_t>(r)))) {
      out.push_back(r);
    }
  }
  return out;
}

}  // namespace sadr::orchestrator
