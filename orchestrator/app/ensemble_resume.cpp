// SPDX-License-Identifier: MIT
// `sadr resume DIR` of an ensemble (DIR/ensemble.json): every realization
// that did not finish runs again (from its checkpoint, if any), then
// DIR/ensemble/ is combined again from the CSV frames.
#include <cstdio>
#include <filesystem>

#include "commands.hpp"
#include "sadr/orchestrator/ensemble_manifest.hpp"
#include "sadr/orchestrator/run_manifest.hpp"
#include "sadr/orchestrator/scene_loader.hpp"
#include "sadr/orchestrator/scene_override.hpp"

namespace sadr::orchestrator {
namespace fs = std::filesystem;

int resume_ensemble(const ServiceOptions& o, const fs::path& dir) {
  const EnsembleManifest manifest = EnsembleManifest::read(dir);
  const Scene scene = load_scene(manifest.scene_path, parse_overrides(manifest.overrides));
  if (scene.source_hash != manifest.scene_hash) {
    throw InvalidArgument((dir / kEnsembleManifestName).string() + ": the scene " +
                          manifest.scene_path + " changed since the ensemble started (hash " +
                          scene.source_hash + ", was " + manifest.scene_hash + ")");
  }
  Plan plan = make_plan(scene);
  const int count = manifest.realizations;
  decide_flow_replay(plan, o.no_flow_replay, count);
  fs::path replay;  // prepared when the first realization needs it
  std::vector<FailedRealization> failed;
  int executed = 0;
  for (int r = 0; r < count && !interrupt_requested(); ++r) {
    const fs::path rd = dir / realization_dir_name(static_cast<std::uint64_t>(r));
    if (realization_finished(rd)) continue;
    ++executed;
    const bool resumed = fs::exists(rd / "checkpoint" / std::string(kCheckpointManifestName));
    RunOptions base;
    base.progress = false;
    // Flow replay: a realization that replayed goes on replaying; one that stepped its
    // fluid (its checkpoint holds the fluid's state) goes on stepping it.
    const bool replays = checkpoint_replays_flow(rd) || (plan.flow_replay && !resumed);
    if (replays && replay.empty()) {
      replay = prepare_flow_replay(scene, plan, o, dir);
      if (replay.empty()) break;  // stopped during the fluid pass
    }
    if (replays) base.flow_replay = replay;
    RunResult res;
    if (auto f = run_ensemble_member(scene, plan, o, r, rd, true, base, {}, res)) {
      std::fprintf(stderr, "sadr: realization %d failed: %s\n", r, f->reason.c_str());
      failed.push_back(std::move(*f));
    } else {
      std::fprintf(stderr, "sadr: realization %d %s\n", r,
                   res.interrupted ? "interrupted"
                   : resumed       ? "resumed and done"
                                   : "done");
    }
  }
  EnsembleManifest::of(scene, count, o.retries, failed).write(dir);
  std::fprintf(stderr, "sadr: resumed %d of %d realizations\n", executed, count);
  if (!failed.empty()) return report_failed_realizations(dir, failed);
  if (interrupt_requested()) return kExitInterrupted;
  return combine_ensemble(dir);
}

}  // namespace sadr::orchestrator
