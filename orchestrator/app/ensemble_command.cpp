// SPDX-License-Identifier: MIT
// `sadr ensemble DIR`: per-frame ensemble mean and variance from the CSV
// frames of realizations run separately (e.g. one Slurm array task each).
// The result equals what `sadr run -r R` writes for the same realizations.
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "cli.hpp"
#include "commands.hpp"
#include "sadr/orchestrator/atomic_file.hpp"
#include "sadr/orchestrator/ensemble_accumulator.hpp"
#include "sadr/orchestrator/ensemble_pool.hpp"
#include "sadr/orchestrator/hash.hpp"
#include "sadr/orchestrator/run_manifest.hpp"
#include "sadr/orchestrator/scene_loader.hpp"
#include "sadr/orchestrator/sweep_frames.hpp"

namespace sadr::orchestrator {
namespace fs = std::filesystem;

int combine_ensemble(const fs::path& dir) {
  std::vector<fs::path> realizations;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.is_directory() && is_realization_dir_name(e.path().filename().string())) {
      realizations.push_back(e.path());
    }
  }
  std::sort(realizations.begin(), realizations.end());
  if (realizations.empty()) {
    throw InvalidArgument("'" + dir.string() + "' holds no realization_NNNN/ folders");
  }
  std::optional<EnsembleAccumulator> acc;
  std::vector<std::uint64_t> ids;
  std::map<std::size_t, fs::path> expected;  // the first realization's frames
  std::size_t used = 0;
  std::string hash, hash_of;  // the effective scene of the first realization with a run.json
  for (const auto& r : realizations) {
    // Never mix runs of different effective scenes (an edited scene, other --set values).
    if (fs::exists(r / "run.json")) {
      std::string h;
      try {
        h = nlohmann::json::parse(read_file_bytes(r / "run.json")).value("scene_hash", "");
      } catch (const nlohmann::json::exception& e) {
        throw InvalidArgument((r / "run.json").string() + ": not valid JSON: " + e.what());
      }
      if (hash.empty()) {
        hash = h;
        hash_of = r.string();
      } else if (!h.empty() && h != hash) {
        throw InvalidArgument(r.string() + " ran the effective scene " + h + ", " + hash_of +
                              " ran " + hash +
                              "; refusing to combine runs of different scenes (or --set values)");
      }
    }
    const auto frames = list_csv_frames(r);
    if (frames.empty()) {
      std::fprintf(stderr, "sadr: %s has no CSV frames (add csv to output.formats); skipped\n",
                   r.string().c_str());
      continue;
    }
    if (used == 0) expected = frames;
    // Every realization must have the same frames: never average a frame
    // over fewer realizations than the others without a word.
    for (const auto& [k, p] : expected) {
      if (!frames.count(k)) {
        throw InvalidArgument(r.string() + ": frame " + p.filename().string() + " is missing (" +
                              expected.at(k).parent_path().parent_path().string() +
                              " has it); every realization needs the same frames");
      }
    }
    for (const auto& [k, p] : frames) {
      if (!expected.count(k)) {
        throw InvalidArgument(p.string() + ": not among the frames of the first realization");
      }
    }
    for (const auto& [index, path] : frames) {
      const CsvFrame f = read_frame_csv(path);  // file:row: column: value on a bad cell
      if (!acc) {
        std::vector<std::string> names;
        for (const auto& s : f.species) names.push_back(s.name);
        acc.emplace(names, f.particles.ids.size());
        ids = f.particles.ids;
      }
      try {
        acc->add(index, f.time, f.species);
      } catch (const Error& e) {
        throw InvalidArgument(path.string() + ": " + e.what());
      }
    }
    ++used;
  }
  if (!acc) throw InvalidArgument("no CSV frames found under '" + dir.string() + "'");
  write_ensemble_frames(*acc, dir, ids);
  std::fprintf(stderr, "sadr: combined %zu realizations into %s\n", used,
               (dir / "ensemble").string().c_str());
  return kExitOk;
}

Subcommand add_ensemble_command(CLI::App& app) {
  auto directory = std::make_shared<std::string>();
  auto* ensemble = app.add_subcommand(
      "ensemble",
      "combine OUTPUT/realization_*/frames/*.csv into OUTPUT/ensemble/ (mean, variance)");
  ensemble->add_option("directory", *directory, "the output directory of the realizations")
      ->required()
      ->check(CLI::ExistingDirectory);

  return {ensemble, [directory] { return combine_ensemble(*directory); }};
}

}  // namespace sadr::orchestrator
