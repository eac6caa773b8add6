// SPDX-License-Identifier: MIT
// Fuzz target: the particle CSV reader. The input is written as the particle
// file of a fixed 2D scene that reads species A from a column `A0`
// (count_column) and loaded with parse_scene; only a sadr::Error may come out.
#include "fuzz_support.hpp"
#include "sadr/common/status.hpp"
#include "sadr/orchestrator/scene_loader.hpp"

namespace {
constexpr std::string_view kScene = R"(name: csv
dimension: 2
box: {lower: [0.0, 0.0], upper: [1.0, 1.0], periodic: [true, false]}
regions:
  - {name: left, shape: box, lower: [0.0, 0.0], upper: [0.5, 1.0]}
particles: {file: particles.csv}
fluid: {backend: static, smoothing_length: 0.3}
species:
  - {name: A, diffusivity: 0.01, initial: [{count_column: A0}]}
time: {coupling_step: 0.1, end: 1.0}
)";
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto& dir = sadr::fuzz::scratch_dir();
  sadr::fuzz::write_file(dir / "particles.csv",
                         std::string_view(reinterpret_cast<const char*>(data), size));
  try {
    (void)sadr::orchestrator::parse_scene(kScene, dir / "csv.yaml");
  } catch (const sadr::Error& e) {
    sadr::fuzz::note_refusal(e.what());
  }
  return 0;
}
