// SPDX-License-Identifier: MIT
// Scratch folders and file reading for the tests of orchestrator/campaign.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace sadr::orchestrator::runs_test {

/// A fresh, empty folder for one test: PREFIX-<pid>-NAME in the temporary directory.
inline std::filesystem::path scratch(const std::string& prefix, const std::string& name) {
  const std::filesystem::path d = std::filesystem::temp_directory_path() /
                                  (prefix + "-" + std::to_string(getpid()) + "-" + name);
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

inline std::string read_all(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace sadr::orchestrator::runs_test
