// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/summary_totals.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "sadr/common/status.hpp"

namespace sadr::orchestrator {
namespace fs = std::filesystem;
namespace {

double number(const nlohmann::json& j, const char* key) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : 0.0;
}

}  // namespace

std::vector<std::string> split_csv_cells(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  for (std::string cell; std::getline(ss, cell, ',');) out.push_back(cell);
  return out;
}

ColumnTotals sum_columns(const fs::path& path, bool ensemble) {
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line)) throw InvalidArgument(path.string() + ": empty file");
  const std::vector<std::string> header = split_csv_cells(line);
  // frames: time,id,kind,x,y,z,vx,vy,vz,density,mass,<species...>;
  // ensemble: time,id,realizations,<s>_mean,<s>_var,...
  const std::size_t first = ensemble ? 3 : 11;
  ColumnTotals t;
  std::vector<std::size_t> cols;
  for (std::size_t c = first; c < header.size(); ++c) {
    const std::string& h = header[c];
    if (ensemble && (h.size() < 5 || h.compare(h.size() - 5, 5, "_mean") != 0)) continue;
    cols.push_back(c);
    t.names.push_back(ensemble ? h.substr(0, h.size() - 5) : h);
  }
  t.totals.assign(cols.size(), 0.0);
  t.amounts.assign(cols.size(), 0.0);
  for (std::size_t row = 0; std::getline(in, line); ++row) {
    const std::vector<std::string> cells = split_csv_cells(line);
    if (cells.size() != header.size()) {
      throw InvalidArgument(path.string() + ":" + std::to_string(row + 2) + ": " +
                            std::to_string(cells.size()) + " columns, expected " +
                            std::to_string(header.size()));
    }
    if (row == 0) t.time = std::stod(cells[0]);
    const double volume = ensemble ? 0.0 : std::stod(cells[10]) / std::stod(cells[9]);
    for (std::size_t k = 0; k < cols.size(); ++k) {
      const double v = std::stod(cells[cols[k]]);
      t.totals[k] += v;
      t.amounts[k] += v * volume;
    }
  }
  return t;
}

nlohmann::json read_run_json(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw InvalidArgument("'" + path.string() + "': cannot open (not a sadr run?)");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InvalidArgument(path.string() + ": not valid JSON: " + e.what());
  }
}

std::vector<fs::path> sorted_files(const fs::path& dir, const std::string& ext) {
  std::vector<fs::path> out;
  if (fs::is_directory(dir)) {
    for (const auto& e : fs::directory_iterator(dir)) {
      if (e.path().extension() == ext) out.push_back(e.path());
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

void ManifestTotals::add(const nlohmann::json& m) {
  steps += number(m, "steps");
  substeps += number(m, "fluid_substeps");
  overlapped += number(m, "overlapped_steps");
  if (m.contains("ssa_events")) {
    events += number(m, "ssa_events");
  } else {
    events_recorded = false;
  }
  time = std::max(time, number(m, "time"));
  if (m.contains("timings_s")) {
    for (const auto& [k, v] : m["timings_s"].items()) timings[k] += v.get<double>();
  }
  statuses.push_back(m.value("status", "?"));
}

}  // namespace sadr::orchestrator
