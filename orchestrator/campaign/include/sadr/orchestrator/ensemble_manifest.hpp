// SPDX-License-Identifier: MIT
/// \file ensemble_manifest.hpp
/// DIR/ensemble.json of `sadr run -r R`: the scene, its overrides, R, the
/// retries and the realizations that failed, which `sadr resume DIR` reads to
/// run or resume every realization that did not finish.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace sadr::orchestrator {

struct Scene;

/// A realization of `sadr run -r R` that failed (the others go on).
struct FailedRealization {
  int realization = 0;
  int exit_code = 0;
  std::string reason;
  int attempts = 1;  ///< attempts made (1 + the retries used)
};

inline constexpr const char* kEnsembleManifestName = "ensemble.json";

struct EnsembleManifest {
  std::string scene_path;  ///< absolute
  std::vector<std::string> overrides;
  std::string scene_hash;
  int realizations = 0;
  int retries = 1;
  std::vector<FailedRealization> failed;

  /// The manifest of an ensemble of `scene` (its absolute path, overrides and hash).
  static EnsembleManifest of(const Scene& scene, int realizations, int retries,
                             std::vector<FailedRealization> failed);
  /// Writes DIR/ensemble.json atomically.
  void write(const std::filesystem::path& dir) const;
  /// Reads DIR/ensemble.json. @throws nlohmann::json::exception on a bad file
  static EnsembleManifest read(const std::filesystem::path& dir);
};

/// Whether `dir` holds an ensemble (DIR/ensemble.json).
[[nodiscard]] bool is_ensemble_dir(const std::filesystem::path& dir);
/// Whether the realization in `rd` finished (its run.json says status ok).
[[nodiscard]] bool realization_finished(const std::filesystem::path& rd);
/// The realizations 0..count-1 of the ensemble in `dir` that did not finish.
[[nodiscard]] std::vector<int> unfinished_realizations(const std::filesystem::path& dir, int count);

}  // namespace sadr::orchestrator
