// SPDX-License-Identifier: MIT
// `sadr ensemble DIR`: per-frame ensemble mean and variance from the CSV
// frames of realizations run separately (e.g. one Slurm array task each).
// The result equals what `sadr run -r R` writes for the same realizations.
#include <cstdio>
#include <filesystem>
#include <map>

#include "commands.hpp"
#include "sadr/orchestrator/atomic_file.hpp"
#include "sadr/orchestrator/ensemble_accumulator.hpp"
#include "sadr/orchestrator/sweep_frames.hpp"

namespace sadr::orchestrator {
namespace fs = std::filesystem;

int cmd_ensemble(const CliOptions& o) {
  const fs::path dir = o.directory;
  std::vector<fs::path> realizations;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.is_directory() && e.path().filename().string().rfind("realization_", 0) == 0) {
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
  for (const auto& r : realizations) {
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
  ensure_directory(dir / "ensemble");
  for (std::size_t k = 0; k < acc->frame_count(); ++k) {
    if (acc->realizations(k) == 0) continue;
    char name[48];
    std::snprintf(name, sizeof name, "ensemble/frame_%06zu.csv", k);
    acc->write_csv(k, dir / name, ids);
  }
  std::fprintf(stderr, "sadr: combined %zu realizations into %s\n", used,
               (dir / "ensemble").string().c_str());
  return kExitOk;
}

}  // namespace sadr::orchestrator
