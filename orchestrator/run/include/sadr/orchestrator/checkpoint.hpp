// SPDX-License-Identifier: MIT
/// \file checkpoint.hpp
/// Checkpoint files: one opaque blob per service (its own exact-restart
/// state, RNG included) plus a versioned JSON manifest that names them.
///
/// Layout in the checkpoint directory:
///   checkpoint.json                 the manifest (replaced atomically)
///   <service>-<step>-<hash8>.blob   e.g. ssa-000000000120-1f3a9c07.blob
/// Blobs are written first, each atomically; then the manifest. Only after
/// the new manifest is durable are the previous checkpoint's blobs deleted,
/// so at every instant checkpoint.json names a complete, valid checkpoint.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "sadr/orchestrator/atomic_file.hpp"

namespace sadr::orchestrator {

/// Version of the manifest layout written by this build.
inline constexpr int kCheckpointFormatVersion = 1;
/// File name of the manifest inside a checkpoint directory.
inline constexpr std::string_view kCheckpointManifestName = "checkpoint.json";

struct CheckpointBlob {
  std::string service;  ///< "fluid", "ssa", ...
  std::string backend;  ///< e.g. "sdpd", "nsm"
  std::string file;     ///< file name, relative to the manifest's directory
  std::uint64_t size = 0;
  std::string hash;  ///< content_hash() of the bytes
};

struct CheckpointManifest {
  int format_version = kCheckpointFormatVersion;
  std::string sadr_version;  ///< build that wrote it
  std::string scene_path;    ///< informational
  std::string scene_hash;    ///< content_hash() of the scene file: must match on resume
  std::uint64_t seed = 0;    ///< realization seed
  std::uint64_t realization = 0;
  std::uint64_t step_index = 0;  ///< coupling steps completed
  double time = 0.0;             ///< simulated time reached [time] (stored exactly)
  std::vector<CheckpointBlob> blobs;

  [[nodiscard]] nlohmann::json to_json() const;
  /// @throws sadr::InvalidArgument naming `source` and the bad field.
  static CheckpointManifest from_json(const nlohmann::json& j, const std::string& source);
};

/// One service's state to save.
struct ServiceBlob {
  std::string backend;
  std::string bytes;  ///< opaque
};

/// Writes the blobs and then the manifest into `directory` (created if
/// needed) as described in the file comment; `manifest.blobs` is filled in.
/// @param blobs service name -> blob
/// @param fault test hook passed to every atomic write (simulated crash)
/// @return the manifest as written
/// @throws IoError on any file-system failure (the previous checkpoint stays valid)
CheckpointManifest write_checkpoint(const std::filesystem::path& directory,
                                    CheckpointManifest manifest,
                                    const std::map<std::string, ServiceBlob>& blobs,
                                    const AtomicWriteFault* fault = nullptr);

struct LoadedCheckpoint {
  CheckpointManifest manifest;
  std::map<std::string, ServiceBlob> blobs;  ///< service name -> blob
};

/// Reads a checkpoint (a manifest path or the directory holding
/// checkpoint.json) and its blobs, checking the format version, each blob's
/// size and hash and, unless `expected_scene_hash` is empty, that the
/// checkpoint was written for the scene with that hash.
/// @throws sadr::InvalidArgument with a message that says what does not match
LoadedCheckpoint load_checkpoint(const std::filesystem::path& path,
                                 std::string_view expected_scene_hash);

/// Refuses a manifest that the scene could not have produced (a hand edit):
/// time not finite or outside [0, end], step_index beyond what the coupling
/// step allows for that time (or 0 for t > 0), seed not the realization's. The field is named.
/// @throws sadr::InvalidArgument
void check_manifest_fits_scene(const CheckpointManifest& manifest, double end_time,
                               double coupling_step, std::size_t output_times,
                               std::uint64_t scene_seed, const std::string& source);

}  // namespace sadr::orchestrator
