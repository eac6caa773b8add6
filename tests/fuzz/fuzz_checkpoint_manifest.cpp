// SPDX-License-Identifier: MIT
// Fuzz target: checkpoint manifests. The input is written as checkpoint.json
// (next to the blob of make_seeds' manifest) and read by
// load_checkpoint, then checked against a scene as `sadr resume` does
// (check_manifest_fits_scene). Only a sadr::Error may come out.
#include "fuzz_support.hpp"
#include "sadr/common/status.hpp"
#include "sadr/orchestrator/checkpoint.hpp"
#include "sadr/orchestrator/seeds.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path dir = [] {
    auto d = sadr::fuzz::scratch_dir() / "checkpoint";
    std::filesystem::create_directories(d);
    sadr::orchestrator::CheckpointManifest m;  // the blob the seed manifest names
    m.seed = sadr::orchestrator::realization_seed(7, 0);
    m.step_index = 2;
    m.time = 0.2;
    sadr::orchestrator::write_checkpoint(d, m, {{"ssa", {"nsm", "blob"}}});
    return d;
  }();
  sadr::fuzz::write_file(dir / "checkpoint.json",
                         std::string_view(reinterpret_cast<const char*>(data), size));
  try {
    const auto loaded = sadr::orchestrator::load_checkpoint(dir, "");
    sadr::orchestrator::check_manifest_fits_scene(loaded.manifest, 1.0, 0.1, 11, 7,
                                                  "checkpoint.json");
  } catch (const sadr::Error& e) {
    sadr::fuzz::note_refusal(e.what());
  }
  return 0;
}
