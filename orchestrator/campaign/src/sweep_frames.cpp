// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/sweep_frames.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <string_view>

#include "sadr/common/status.hpp"

namespace sadr::orchestrator {
namespace fs = std::filesystem;
namespace {

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> out;
  for (std::size_t start = 0;;) {
    const std::size_t comma = line.find(',', start);
    out.push_back(line.substr(start, comma == std::string_view::npos ? comma : comma - start));
    if (comma == std::string_view::npos) return out;
    start = comma + 1;
  }
}

}  // namespace

CsvFrame read_frame_csv(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InvalidArgument(path.string() + ": cannot be opened");
  std::string line;
  if (!std::getline(in, line)) throw InvalidArgument(path.string() + ": empty file");
  const auto header_views = split(line);
  const std::vector<std::string> header(header_views.begin(), header_views.end());
  // time,id,kind,x,y,z,vx,vy,vz,density,mass,<species...>
  constexpr std::size_t kFirstSpecies = 11;
  static constexpr std::array<std::string_view, kFirstSpecies> kFixed{
      "time", "id", "kind", "x", "y", "z", "vx", "vy", "vz", "density", "mass"};
  bool ok = header.size() >= kFirstSpecies;
  for (std::size_t c = 0; ok && c < kFirstSpecies; ++c) ok = header[c] == kFixed[c];
  if (!ok) {
    throw InvalidArgument(path.string() +
                          ":1: not a sadr frame CSV (expected the header "
                          "time,id,kind,x,y,z,vx,vy,vz,density,mass,<species...>)");
  }
  CsvFrame f;
  f.particles.dimension = 3;
  for (std::size_t c = kFirstSpecies; c < header.size(); ++c) f.species.push_back({header[c], {}});
  std::size_t row = 1;
  std::vector<double> cells(header.size());
  while (std::getline(in, line)) {
    ++row;
    if (line.empty()) continue;
    const auto text = split(line);
    const std::string where = path.string() + ":" + std::to_string(row) + ": ";
    if (text.size() != header.size()) {
      throw InvalidArgument(where + std::to_string(text.size()) + " columns, expected " +
                            std::to_string(header.size()) + " (as in the header)");
    }
    for (std::size_t c = 0; c < text.size(); ++c) {
      double v = 0;
      const auto [end, ec] = std::from_chars(text[c].data(), text[c].data() + text[c].size(), v);
      if (ec != std::errc() || end != text[c].data() + text[c].size() || !std::isfinite(v)) {
        throw InvalidArgument(where + "column '" + header[c] + "': '" + std::string(text[c]) +
                              "' is not a finite number");
      }
      cells[c] = v;
    }
    if (row == 2) {
      f.time = cells[0];
    } else if (cells[0] != f.time) {
      throw InvalidArgument(where + "column 'time': " + std::string(text[0]) +
                            " differs from the first row's time");
    }
    if (cells[1] < 0 || cells[1] != std::floor(cells[1]) || cells[2] < 0 || cells[2] > 3 ||
        cells[2] != std::floor(cells[2])) {
      throw InvalidArgument(where + "id or kind is not a whole number in range");
    }
    f.particles.ids.push_back(static_cast<std::uint64_t>(cells[1]));
    f.particles.kinds.push_back(static_cast<ParticleKind>(static_cast<int>(cells[2])));
    for (std::size_t a = 3; a < 6; ++a) f.particles.positions.push_back(cells[a]);
    for (std::size_t a = 6; a < 9; ++a) f.particles.velocities.push_back(cells[a]);
    f.particles.densities.push_back(cells[9]);
    f.particles.masses.push_back(cells[10]);
    for (std::size_t c = kFirstSpecies; c < cells.size(); ++c) {
      f.species[c - kFirstSpecies].values.push_back(cells[c]);
    }
  }
  if (f.particles.ids.empty())
    throw InvalidArgument(path.string() + ": header only, no particle rows");
  return f;
}

std::map<std::size_t, fs::path> list_csv_frames(const fs::path& dir) {
  std::map<std::size_t, fs::path> out;
  if (!fs::is_directory(dir / "frames")) return out;
  for (const auto& e : fs::directory_iterator(dir / "frames")) {
    const std::string name = e.path().filename().string();
    if (e.path().extension() != ".csv" || name.rfind("frame_", 0) != 0) continue;
    const std::string digits = e.path().stem().string().substr(6);
    std::size_t k = 0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), k);
    if (ec != std::errc() || end != digits.data() + digits.size()) continue;
    out[k] = e.path();
  }
  return out;
}

}  // namespace sadr::orchestrator
