// SPDX-License-Identifier: MIT
/// \file summary_totals.hpp
/// The figures of `sadr summary`: column sums of a frame CSV and the counters
/// and timings of run.json manifests summed (run_summary.hpp prints them).
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace sadr::orchestrator {

/// The cells of one line of a frame CSV (no quoting: sadr writes none).
[[nodiscard]] std::vector<std::string> split_csv_cells(const std::string& line);

/// Column sums of a frame CSV: the time (first column of the first row) and,
/// per species column, the sum over the particles and (frames only) the sum
/// of value x volume m / rho (the amount, for a concentration).
struct ColumnTotals {
  double time = 0;
  std::vector<std::string> names;
  std::vector<double> totals, amounts;
};

/// Sums a frame CSV (`ensemble`: an ensemble/frame_*.csv, its *_mean columns).
/// @throws InvalidArgument on an empty file or a row with another column count
[[nodiscard]] ColumnTotals sum_columns(const std::filesystem::path& path, bool ensemble);

/// A run.json. @throws InvalidArgument when it cannot be opened or parsed
[[nodiscard]] nlohmann::json read_run_json(const std::filesystem::path& path);

/// The files of `dir` with extension `ext` ("" if none), sorted.
[[nodiscard]] std::vector<std::filesystem::path> sorted_files(const std::filesystem::path& dir,
                                                              const std::string& ext);

/// Sums the counters and timings of several manifests (one for a run).
struct ManifestTotals {
  double steps = 0, substeps = 0, overlapped = 0, events = 0, time = 0;
  bool events_recorded = true;  ///< every manifest had ssa_events
  std::map<std::string, double> timings;
  std::vector<std::string> statuses;
  void add(const nlohmann::json& m);
};

}  // namespace sadr::orchestrator
