// SPDX-License-Identifier: MIT
// Flow replay in an ensemble (flow_replay.hpp): the fluid-only pass that writes
// OUTPUT/flow_replay.bin, and which realizations replay it.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <thread>

#include "commands.hpp"
#include "sadr/common/log.hpp"
#include "sadr/orchestrator/checkpoint.hpp"
#include "sadr/orchestrator/flow_replay.hpp"
#include "sadr/orchestrator/scene_messages.hpp"

namespace sadr::orchestrator {
namespace fs = std::filesystem;

fs::path flow_replay_path(const fs::path& dir) {
  return dir / std::string(kFlowTapeName);
}

fs::path prepare_flow_replay(const Scene& scene, const Plan& plan, const ServiceOptions& o,
                             const fs::path& dir) {
  const fs::path path = flow_replay_path(dir);
  if (fs::exists(path)) {  // an earlier pass (sadr resume): its header must match this scene
    const FlowTapeReader existing(path, scene_meaning_hash(scene, plan));
    if (!o.quiet) {
      std::fprintf(stderr, "sadr: flow replay: the fluid's answers from %s (%llu records)\n",
                   path.string().c_str(),
                   static_cast<unsigned long long>(existing.header().records));
    }
    return path;
  }
  // The pass runs alone: its fluid takes every core unless told otherwise (results do not
  // depend on the thread count; the realizations keep theirs).
  const bool own_threads = std::getenv("SADR_FLUID_THREADS") == nullptr;
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  if (own_threads) setenv("SADR_FLUID_THREADS", std::to_string(cores).c_str(), 1);
  struct Unset {
    bool on;
    ~Unset() {
      if (on) unsetenv("SADR_FLUID_THREADS");
    }
  } unset{own_threads};
  if (!o.quiet) std::fprintf(stderr, "sadr: flow replay: computing the fluid once\n");
  Plan fluid_only = plan;
  fluid_only.ssa_service = false;
  ServiceSet services(o.mode, fluid_only, o.remote, "flow");
  RecordFlowOptions ro;
  ro.path = path;
  ro.timeout = std::chrono::milliseconds(static_cast<long>(o.timeout_s * 1000));
  ro.liveness = [&services] { services.check_alive(); };
  ro.interrupt = &interrupt_flag();
  const RecordedFlow rec = record_flow(scene, plan, services.endpoints().fluid, ro);
  services.stop();
  if (!rec.complete) return {};
  if (!o.quiet) {
    std::fprintf(stderr,
                 "sadr: flow replay: %llu fluid calls recorded in %.1f s, %.1f MB in %s; "
                 "the realizations replay them\n",
                 static_cast<unsigned long long>(rec.records), rec.seconds,
                 static_cast<double>(rec.bytes) / 1e6, path.string().c_str());
  }
  return path;
}

bool checkpoint_replays_flow(const fs::path& realization_dir) {
  const fs::path manifest = realization_dir / "checkpoint" / std::string(kCheckpointManifestName);
  if (!fs::exists(manifest)) return false;
  const LoadedCheckpoint cp = load_checkpoint(manifest, "");
  const auto blob = cp.blobs.find("fluid");
  return blob != cp.blobs.end() && is_flow_replay_snapshot(blob->second.bytes);
}

}  // namespace sadr::orchestrator
