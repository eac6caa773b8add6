// SPDX-License-Identifier: MIT
// Fuzz target: the ensemble reader. The input is a CSV frame as `sadr run`
// writes it (frame_writers.hpp), read by read_frame_csv and added twice to an
// EnsembleAccumulator (two realizations of frame 0), then written back, as
// `sadr ensemble` does. Only a sadr::Error may come out.
#include "fuzz_support.hpp"
#include "sadr/common/status.hpp"
#include "sadr/orchestrator/ensemble_accumulator.hpp"
#include "sadr/orchestrator/sweep_frames.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto& dir = sadr::fuzz::scratch_dir();
  const auto path = dir / "frame_000000.csv";
  sadr::fuzz::write_file(path, std::string_view(reinterpret_cast<const char*>(data), size));
  try {
    const auto f = sadr::orchestrator::read_frame_csv(path);
    std::vector<std::string> names;
    for (const auto& s : f.species) names.push_back(s.name);
    sadr::orchestrator::EnsembleAccumulator acc(names, f.particles.ids.size());
    acc.add(0, f.time, f.species);
    acc.add(0, f.time, f.species);
    acc.write_csv(0, dir / "ensemble.csv", f.particles.ids);
  } catch (const sadr::Error& e) {
    sadr::fuzz::note_refusal(e.what());
  }
  return 0;
}
