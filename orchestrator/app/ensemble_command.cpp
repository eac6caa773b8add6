// SPDX-License-Identifier: MIT
// `sadr ensemble DIR`: per-frame ensemble mean and variance from the CSV
// frames of realizations run separately (e.g. one Slurm array task each).
// The result equals what `sadr run -r R` writes for the same realizations.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

#include "commands.hpp"
#include "csv_cells.hpp"
#include "sadr/orchestrator/atomic_file.hpp"
#include "sadr/orchestrator/ensemble_accumulator.hpp"

namespace sadr::orchestrator {
namespace fs = std::filesystem;
namespace {

/// One CSV frame: its time, the particle ids and the species columns.
struct CsvFrame {
  double time = 0;
  std::vector<std::uint64_t> ids;
  std::vector<SpeciesColumn> species;
};

CsvFrame read_frame(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line)) throw InvalidArgument(path.string() + ": empty file");
  const auto header = split_csv_line(line);
  // time,id,kind,x,y,z,vx,vy,vz,density,mass,<species...>
  constexpr std::size_t kFirstSpecies = 11;
  if (header.size() < kFirstSpecies || header[0] != "time" || header[10] != "mass") {
    throw InvalidArgument(path.string() +
                          ":1: not a sadr frame CSV (expected the header "
                          "time,id,kind,x,y,z,vx,vy,vz,density,mass,...)");
  }
  CsvFrame f;
  for (std::size_t c = kFirstSpecies; c < header.size(); ++c) f.species.push_back({header[c], {}});
  std::size_t row = 1;
  while (std::getline(in, line)) {
    ++row;
    const auto cells = split_csv_line(line);
    if (cells.size() != header.size()) {
      throw InvalidArgument(path.string() + ":" + std::to_string(row) + ": " +
                            std::to_string(cells.size()) + " columns, expected " +
                            std::to_string(header.size()));
    }
    f.time = std::stod(cells[0]);
    f.ids.push_back(std::stoull(cells[1]));
    for (std::size_t c = kFirstSpecies; c < cells.size(); ++c) {
      f.species[c - kFirstSpecies].values.push_back(std::stod(cells[c]));
    }
  }
  return f;
}

}  // namespace

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
  std::size_t used = 0;
  for (const auto& r : realizations) {
    std::vector<fs::path> frames;
    if (fs::exists(r / "frames")) {
      for (const auto& e : fs::directory_iterator(r / "frames")) {
        if (e.path().extension() == ".csv") frames.push_back(e.path());
      }
    }
    if (frames.empty()) {
      std::fprintf(stderr, "sadr: %s has no CSV frames (add csv to output.formats); skipped\n",
                   r.string().c_str());
      continue;
    }
    std::sort(frames.begin(), frames.end());
    for (const auto& path : frames) {
      // frame_NNNNNN.csv -> NNNNNN is the output index
      const std::size_t index = std::stoul(path.stem().string().substr(6));
      CsvFrame f = read_frame(path);
      if (!acc) {
        std::vector<std::string> names;
        for (const auto& s : f.species) names.push_back(s.name);
        acc.emplace(names, f.ids.size());
        ids = f.ids;
      }
      acc->add(index, f.time, f.species);
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
