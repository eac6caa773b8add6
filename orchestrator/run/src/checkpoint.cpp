// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/checkpoint.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>

#include "sadr/common/build_info.hpp"
#include "sadr/common/status.hpp"
#include "sadr/orchestrator/hash.hpp"
#include "sadr/orchestrator/seeds.hpp"

namespace sadr::orchestrator {

namespace {

std::string hex_double(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%a", v);
  return buf;
}

template <typename T>
T field(const nlohmann::json& j, const char* key, const std::string& source) {
  if (!j.contains(key)) {
    throw InvalidArgument("checkpoint manifest '" + source + "': missing field '" + key + "'");
  }
  try {
    return j.at(key).get<T>();
  } catch (const nlohmann::json::exception& e) {
    throw InvalidArgument("checkpoint manifest '" + source + "': field '" + key +
                          "' has the wrong type (" + e.what() + ")");
  }
}

/// "<service>-<step, 12 digits>-<first 8 hex digits of the content hash>.blob":
/// a new checkpoint never overwrites a blob the previous manifest names,
/// unless the bytes are identical.
std::string blob_name(const std::string& service, std::uint64_t step, const std::string& hash) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%012llu", static_cast<unsigned long long>(step));
  return service + "-" + buf + "-" + hash.substr(hash.size() - 8) + ".blob";
}

}  // namespace

nlohmann::json CheckpointManifest::to_json() const {
  nlohmann::json blobs_json = nlohmann::json::array();
  for (const auto& b : blobs) {
    blobs_json.push_back({{"service", b.service},
                          {"backend", b.backend},
                          {"file", b.file},
                          {"size", b.size},
                          {"hash", b.hash}});
  }
  return {{"format", "sadr-checkpoint"},
          {"format_version", format_version},
          {"sadr_version", sadr_version},
          {"scene_path", scene_path},
          {"scene_hash", scene_hash},
          {"seed", seed},
          {"realization", realization},
          {"step_index", step_index},
          {"time", time},
          {"time_hex", hex_double(time)},
          {"blobs", blobs_json}};
}

CheckpointManifest CheckpointManifest::from_json(const nlohmann::json& j,
                                                 const std::string& source) {
  if (!j.is_object() || j.value("format", "") != "sadr-checkpoint") {
    throw InvalidArgument("'" + source +
                          "' is not a sadr checkpoint manifest (no \"format\": "
                          "\"sadr-checkpoint\")");
  }
  CheckpointManifest m;
  m.format_version = field<int>(j, "format_version", source);
  if (m.format_version != kCheckpointFormatVersion) {
    throw InvalidArgument("checkpoint '" + source + "' has format version " +
                          std::to_string(m.format_version) + "; this build reads version " +
                          std::to_string(kCheckpointFormatVersion) +
                          " only (resume with the sadr version that wrote it: " +
                          j.value("sadr_version", std::string("unknown")) + ")");
  }
  m.sadr_version = field<std::string>(j, "sadr_version", source);
  m.scene_path = field<std::string>(j, "scene_path", source);
  m.scene_hash = field<std::string>(j, "scene_hash", source);
  m.seed = field<std::uint64_t>(j, "seed", source);
  m.realization = field<std::uint64_t>(j, "realization", source);
  m.step_index = field<std::uint64_t>(j, "step_index", source);
  // The hex form is exact; the decimal one is for people.
  const std::string hex = field<std::string>(j, "time_hex", source);
  char* end = nullptr;
  m.time = std::strtod(hex.c_str(), &end);
  if (end == hex.c_str() || *end != '\0') {
    throw InvalidArgument("checkpoint manifest '" + source + "': time_hex '" + hex +
                          "' is not a hexadecimal floating-point number");
  }
  if (j.contains("time") && (!j.at("time").is_number() || j.at("time").get<double>() != m.time)) {
    throw InvalidArgument("checkpoint manifest '" + source + "': field 'time' (" +
                          j.at("time").dump().substr(0, 64) + ") disagrees with 'time_hex' (" +
                          hex.substr(0, 64) + " = " + format_value(m.time) +
                          "); the manifest was edited by hand");
  }
  const auto& blobs = j.contains("blobs") ? j.at("blobs") : nlohmann::json();
  if (!blobs.is_array()) {
    throw InvalidArgument("checkpoint manifest '" + source + "': 'blobs' must be a list");
  }
  for (const auto& b : blobs) {
    m.blobs.push_back(
        {field<std::string>(b, "service", source), field<std::string>(b, "backend", source),
         field<std::string>(b, "file", source), field<std::uint64_t>(b, "size", source),
         field<std::string>(b, "hash", source)});
  }
  return m;
}

CheckpointManifest write_checkpoint(const std::filesystem::path& directory,
                                    CheckpointManifest manifest,
                                    const std::map<std::string, ServiceBlob>& blobs,
                                    const AtomicWriteFault* fault) {
  ensure_directory(directory);
  const std::filesystem::path manifest_path = directory / kCheckpointManifestName;
  // Blob files the current (previous) checkpoint uses: deleted only at the end.
  std::set<std::string> previous;
  if (std::filesystem::exists(manifest_path)) {
    try {
      const auto old = CheckpointManifest::from_json(
          nlohmann::json::parse(read_file_bytes(manifest_path)), manifest_path.string());
      for (const auto& b : old.blobs) previous.insert(b.file);
    } catch (const std::exception&) {
      // An unreadable old manifest is replaced; its blobs are left alone.
    }
  }
  manifest.format_version = kCheckpointFormatVersion;
  if (manifest.sadr_version.empty()) manifest.sadr_version = kBuildVersion;
  manifest.blobs.clear();
  for (const auto& [service, blob] : blobs) {
    const std::string hash = content_hash(blob.bytes);
    CheckpointBlob entry{service, blob.backend, blob_name(service, manifest.step_index, hash),
                         blob.bytes.size(), hash};
    write_file_atomic(directory / entry.file, blob.bytes, fault);
    manifest.blobs.push_back(entry);
  }
  write_file_atomic(manifest_path, manifest.to_json().dump(2) + "\n", fault);
  for (const auto& file : previous) {
    bool still_used = false;
    for (const auto& b : manifest.blobs) still_used = still_used || b.file == file;
    std::error_code ec;
    if (!still_used) std::filesystem::remove(directory / file, ec);
  }
  return manifest;
}

void check_manifest_fits_scene(const CheckpointManifest& m, double end_time, double coupling_step,
                               std::size_t output_times, std::uint64_t scene_seed,
                               const std::string& source) {
  auto refuse = [&](const std::string& field, const std::string& why) {
    throw InvalidArgument("checkpoint manifest '" + source + "': field '" + field + "' " + why +
                          " (a hand-edited or foreign checkpoint; resume from one written by "
                          "the run)");
  };
  const double snap = 1e-9 * std::max(end_time, coupling_step);
  if (!std::isfinite(m.time) || m.time < 0.0 || m.time > end_time + snap) {
    refuse("time", "= " + format_value(m.time) + " is outside the scene's [0, " +
                       format_value(end_time) + "]");
  }
  // Steps are at most one coupling step long and are cut at output times (a
  // scene without fluid stepping may take longer ones): at least one step
  // reaches any t > 0, at most ceil(t / tau) + outputs + 1.
  const double fewest = m.time > 0.0 ? 1.0 : 0.0;
  const double most =
      std::ceil(m.time / coupling_step * (1.0 + 1e-9)) + static_cast<double>(output_times) + 1.0;
  const auto steps = static_cast<double>(m.step_index);
  if (steps < fewest || steps > most) {
    refuse("step_index", "= " + std::to_string(m.step_index) + " does not fit time " +
                             format_value(m.time) + " with coupling steps of " +
                             format_value(coupling_step) + " (allowed: " + format_value(fewest) +
                             " to " + format_value(most) + ")");
  }
  if (m.seed != realization_seed(scene_seed, m.realization)) {
    refuse("seed", "= " + std::to_string(m.seed) + " is not the seed of realization " +
                       std::to_string(m.realization) + " of this scene (" +
                       std::to_string(realization_seed(scene_seed, m.realization)) + ")");
  }
}

LoadedCheckpoint load_checkpoint(const std::filesystem::path& path,
                                 std::string_view expected_scene_hash) {
  const std::filesystem::path manifest_path =
      std::filesystem::is_directory(path) ? path / kCheckpointManifestName : path;
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(read_file_bytes(manifest_path));
  } catch (const nlohmann::json::parse_error& e) {
    throw InvalidArgument("checkpoint manifest '" + manifest_path.string() +
                          "' is not valid JSON: " + e.what());
  }
  LoadedCheckpoint out;
  out.manifest = CheckpointManifest::from_json(j, manifest_path.string());
  const auto& m = out.manifest;
  if (!expected_scene_hash.empty() && m.scene_hash != expected_scene_hash) {
    throw InvalidArgument("checkpoint '" + manifest_path.string() +
                          "' was written for a different scene: its scene hash is " + m.scene_hash +
                          " (scene '" + m.scene_path + "'), the scene given has " +
                          std::string(expected_scene_hash) +
                          "; resume with the unchanged scene file that started the run");
  }
  const auto dir = manifest_path.parent_path();
  for (const auto& b : m.blobs) {
    const std::string bytes = read_file_bytes(dir / b.file);
    if (bytes.size() != b.size || content_hash(bytes) != b.hash) {
      throw InvalidArgument("checkpoint blob '" + (dir / b.file).string() + "' of service '" +
                            b.service + "' is corrupt: " + std::to_string(bytes.size()) +
                            " bytes with hash " + content_hash(bytes) + ", manifest says " +
                            std::to_string(b.size) + " bytes with hash " + b.hash);
    }
    out.blobs[b.service] = ServiceBlob{b.backend, bytes};
  }
  return out;
}

}  // namespace sadr::orchestrator
