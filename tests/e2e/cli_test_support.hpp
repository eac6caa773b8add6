// SPDX-License-Identifier: MIT
/// \file cli_test_support.hpp
/// Helpers shared by the CLI end-to-end tests: locate the built executables,
/// run a command with its output captured, per-test scratch directories, and
/// frame comparison.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "sadr/orchestrator/service_process.hpp"

namespace sadr::e2e {
namespace fs = std::filesystem;

inline std::string bin(const char* name) {
  return std::string(SADR_BINARY_DIR) + "/bin/" + name;
}

inline std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Runs a shell command; returns its exit code; output goes to `log`.
inline int run(const std::string& cmd, const fs::path& log) {
  const int rc = std::system((cmd + " > '" + log.string() + "' 2>&1").c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

/// A fresh directory per test.
inline fs::path scratch(const std::string& name) {
  const fs::path d =
      fs::temp_directory_path() / ("sadr-cli-" + std::to_string(getpid()) + "-" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

inline fs::path write_scene(const fs::path& dir, const std::string& text,
                            const std::string& name = "scene.yaml") {
  const fs::path p = dir / name;
  std::ofstream(p) << text;
  // tests/e2e/compare_builds.py runs every e2e scene on two builds: with
  // SADR_SCENE_DUMP set, each scene a test writes is also kept there.
  if (const char* dump = std::getenv("SADR_SCENE_DUMP"); dump != nullptr && *dump != '\0') {
    fs::create_directories(dump);
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const std::string test = info != nullptr
                                 ? std::string(info->test_suite_name()) + "." + info->name()
                                 : std::string("no_test");
    std::string file = test + "." + name;  // parameterised tests: "Suite/Name.Test/0"
    std::replace(file.begin(), file.end(), '/', '_');
    std::ofstream(fs::path(dump) / file) << text;
  }
  return p;
}

inline std::vector<fs::path> frames(const fs::path& out) {
  std::vector<fs::path> f;
  for (const auto& e : fs::directory_iterator(out / "frames")) f.push_back(e.path());
  std::sort(f.begin(), f.end());
  return f;
}

inline void expect_same_frames(const fs::path& a, const fs::path& b) {
  const auto fa = frames(a), fb = frames(b);
  ASSERT_EQ(fa.size(), fb.size());
  ASSERT_FALSE(fa.empty());
  for (std::size_t i = 0; i < fa.size(); ++i) {
    EXPECT_EQ(fa[i].filename(), fb[i].filename());
    EXPECT_TRUE(read_file(fa[i]) == read_file(fb[i])) << fa[i] << " differs from " << fb[i];
  }
}

/// One frame CSV as columns by header name (every value parsed as a double).
struct CsvFrame {
  std::vector<std::string> names;
  std::vector<std::vector<double>> columns;
  [[nodiscard]] const std::vector<double>& column(const std::string& name) const {
    const auto it = std::find(names.begin(), names.end(), name);
    if (it == names.end()) throw std::runtime_error("no CSV column '" + name + "'");
    return columns[static_cast<std::size_t>(it - names.begin())];
  }
  [[nodiscard]] std::size_t rows() const { return columns.empty() ? 0 : columns[0].size(); }
};

/// `s` with the first `from` replaced by `to` (edits a shipped example for a test).
inline std::string replace_once(std::string s, const std::string& from, const std::string& to) {
  const auto at = s.find(from);
  if (at == std::string::npos) throw std::runtime_error("'" + from + "' not in the example");
  return s.replace(at, from.size(), to);
}

inline CsvFrame read_csv(const fs::path& p) {
  std::istringstream in(read_file(p));
  CsvFrame f;
  std::string line, cell;
  std::getline(in, line);
  std::istringstream h(line);
  while (std::getline(h, cell, ',')) f.names.push_back(cell);
  f.columns.resize(f.names.size());
  while (std::getline(in, line)) {
    std::istringstream r(line);
    for (std::size_t c = 0; c < f.names.size() && std::getline(r, cell, ','); ++c) {
      f.columns[c].push_back(std::stod(cell));
    }
  }
  return f;
}

/// Runs `sadr_run` (ending in options) against fluid_service and ssa_service
/// started here on tcp loopback (remote mode), output in `out`, log in out.log.
inline int run_with_tcp_services(const std::string& sadr_run, const fs::path& out) {
  orchestrator::ServiceProcess ssa(bin("ssa_service"), {"--endpoint", "tcp://127.0.0.1:*"},
                                   "ssa_service");
  orchestrator::ServiceProcess fluid(bin("fluid_service"), {"--endpoint", "tcp://127.0.0.1:*"},
                                     "fluid_service");
  return run(
      sadr_run + "--ssa " + ssa.endpoint() + " --fluid " + fluid.endpoint() + " -o " + out.string(),
      fs::path(out.string() + ".log"));
}

}  // namespace sadr::e2e
