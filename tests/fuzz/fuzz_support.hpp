// SPDX-License-Identifier: MIT
/// \file fuzz_support.hpp
/// What the fuzz targets share: splitting one input into several messages, a
/// per-process scratch directory for targets that read files, the small scene
/// the message targets start from, and the rule for what a target may throw.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

namespace sadr::fuzz {

/// An input as a list of chunks, each `[u32 little-endian length][bytes]`; a
/// length beyond the end takes what is left. make_seeds writes inputs this way
/// (join_chunks), so a seed is a valid message sequence the fuzzer mutates.
inline std::vector<std::string_view> split_chunks(const std::uint8_t* data, std::size_t size,
                                                  std::size_t max_chunks = 16) {
  std::vector<std::string_view> out;
  std::size_t at = 0;
  while (at < size && out.size() < max_chunks) {
    std::uint32_t n = 0;
    for (int b = 0; b < 4 && at < size; ++b, ++at) n |= std::uint32_t{data[at]} << (8 * b);
    const std::size_t len = std::min<std::size_t>(n, size - at);
    out.emplace_back(reinterpret_cast<const char*>(data) + at, len);
    at += len;
  }
  return out;
}

inline std::string join_chunks(const std::vector<std::string>& chunks) {
  std::string out;
  for (const auto& c : chunks) {
    const auto n = static_cast<std::uint32_t>(c.size());
    for (int b = 0; b < 4; ++b) out.push_back(static_cast<char>((n >> (8 * b)) & 0xff));
    out += c;
  }
  return out;
}

/// A scratch directory of this process (removed by nobody: it lives under
/// TMPDIR and holds a few small files that every input overwrites).
inline const std::filesystem::path& scratch_dir() {
  static const std::filesystem::path dir = [] {
    auto d = std::filesystem::temp_directory_path() / ("sadr-fuzz-" + std::to_string(getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

inline void write_file(const std::filesystem::path& path, std::string_view bytes) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

/// With SADR_FUZZ_VERBOSE set, prints why an input was refused (to check that
/// seeds reach deep: a seed refused early covers little).
inline void note_refusal(std::string_view what) {
  static const bool verbose = std::getenv("SADR_FUZZ_VERBOSE") != nullptr;
  if (verbose) {
    std::fprintf(stderr, "refused: %.*s\n", static_cast<int>(what.size()), what.data());
  }
}

/// The scene every message target starts from: 25 fixed particles of a 2D
/// periodic box (static backend), stochastic A (decays) and deterministic B,
/// so both services get an Init, a graph and species. Small so that an input
/// runs in microseconds.
inline constexpr std::string_view kSmallScene = R"(name: fuzz
dimension: 2
box: {lower: [0.0, 0.0], upper: [1.0, 1.0], periodic: [true, true]}
regions:
  - {name: left, shape: box, lower: [0.0, 0.0], upper: [0.5, 1.0]}
particles:
  spacing: 0.2
  density: 1.0
fluid: {backend: static, h_over_dx: 2.0}
species:
  - {name: A, stochastic: true, diffusivity: 0.01, initial: [{count: 3}]}
  - {name: B, stochastic: false, diffusivity: 0.01, initial: [{concentration: 2.0}]}
reactions:
  - {name: decay_A, equation: "A -> 0", rate: 1.0}
  - {name: decay_B, equation: "B -> 0", rate: 1.0, regions: [left]}
time: {coupling_step: 0.05, end: 0.2}
output: {every: 0.1, checkpoint_every: 0.1}
seed: 7
)";

}  // namespace sadr::fuzz
