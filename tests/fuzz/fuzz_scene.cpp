// SPDX-License-Identifier: MIT
// Fuzz target: the scene loader on YAML text (parse_scene), then the plan and
// the work estimate that `sadr validate` computes from it. The only allowed
// failure is a sadr::Error (a diagnosed scene error); any other exception
// escapes and libFuzzer reports it. Seeds: the examples and small scenes.
#include "fuzz_support.hpp"
#include "sadr/common/status.hpp"
#include "sadr/orchestrator/plan.hpp"
#include "sadr/orchestrator/scene_loader.hpp"
#include "sadr/orchestrator/work_estimate.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const auto scene = sadr::orchestrator::parse_scene(text, sadr::fuzz::scratch_dir() / "s.yaml");
    const auto plan = sadr::orchestrator::make_plan(scene);
    (void)plan.lines();
  } catch (const sadr::Error& e) {
    sadr::fuzz::note_refusal(e.what());
  }
  return 0;
}
