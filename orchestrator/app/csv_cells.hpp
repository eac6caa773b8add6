// SPDX-License-Identifier: MIT
/// \file csv_cells.hpp
/// The cells of one line of a frame CSV (no quoting: sadr writes none).
#pragma once

#include <sstream>
#include <string>
#include <vector>

namespace sadr::orchestrator {

inline std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  for (std::string cell; std::getline(ss, cell, ',');) out.push_back(cell);
  return out;
}

}  // namespace sadr::orchestrator
