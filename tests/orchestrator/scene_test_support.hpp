// SPDX-License-Identifier: MIT
// Shared scene text for the orchestrator scene tests.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

namespace sadr::orchestrator::test {

/// A small valid 1D scene; line numbers are referred to by the malformed-scene
/// table, so keep them stable (the number after each line is its line).
inline const std::string kBaseScene =
    "dimension: 1\n"                                              // 1
    "box:\n"                                                      // 2
    "  lower: [0.0]\n"                                            // 3
    "  upper: [1.0]\n"                                            // 4
    "regions:\n"                                                  // 5
    "  - {name: left, shape: box, lower: [0.0], upper: [0.0]}\n"  // 6
    "particles:\n"                                                // 7
    "  spacing: 0.25\n"                                           // 8
    "  fill:\n"                                                   // 9
    "    - {region: left, kind: wall}\n"                          // 10
    "    - {kind: fluid}\n"                                       // 11
    "fluid:\n"                                                    // 12
    "  backend: static\n"                                         // 13
    "  smoothing_length: 0.45\n"                                  // 14
    "species:\n"                                                  // 15
    "  - name: A\n"                                               // 16
    "    diffusivity: 0.1\n"                                      // 17
    "    boundaries:\n"                                           // 18
    "      - {region: left, condition: dirichlet, value: 4}\n"    // 19
    "  - name: B\n"                                               // 20
    "    stochastic: false\n"                                     // 21
    "    diffusivity: 0.2\n"                                      // 22
    "reactions:\n"                                                // 23
    "  - {equation: \"A -> 0\", rate: 1.0}\n"                     // 24
    "time:\n"                                                     // 25
    "  coupling_step: 0.1\n"                                      // 26
    "  end: 1.0\n";                                               // 27

/// `text` with the single occurrence of `from` replaced by `to`.
inline std::string replace_once(const std::string& text, const std::string& from,
                                const std::string& to) {
  const auto pos = text.find(from);
  if (pos == std::string::npos || text.find(from, pos + 1) != std::string::npos) {
    throw std::logic_error("test edit: '" + from + "' must occur exactly once");
  }
  return text.substr(0, pos) + to + text.substr(pos + from.size());
}

/// Directory of the scene fixtures (tests/data/scenes).
inline std::filesystem::path scene_data_dir() {
  return std::filesystem::path(SADR_SOURCE_DIR) / "tests" / "data" / "scenes";
}

}  // namespace sadr::orchestrator::test
