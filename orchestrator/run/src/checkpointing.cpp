// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/checkpointing.hpp"

#include <map>

#include "sadr/common/log.hpp"
#include "sadr/common/status.hpp"

namespace sadr::orchestrator {

std::filesystem::path save_checkpoint(const Scene& scene, const CheckpointPoint& at,
                                      FluidService* fluid, SsaService* ssa,
                                      const std::filesystem::path& output_dir,
                                      const std::string& control_state) {
  CheckpointManifest m;
  m.scene_path = std::filesystem::absolute(scene.source_path).string();
  m.scene_hash = scene.source_hash;
  m.seed = at.seed;
  m.realization = at.realization;
  m.step_index = at.step_index;
  m.time = at.time;
  std::map<std::string, ServiceBlob> blobs;
  if (fluid) blobs["fluid"] = ServiceBlob{scene.fluid.backend, fluid->snapshot(at.step_index)};
  if (ssa) blobs["ssa"] = ServiceBlob{"nsm", ssa->snapshot(at.step_index)};
  if (!control_state.empty()) blobs["step_control"] = ServiceBlob{"controller", control_state};
  const auto dir = output_dir / "checkpoint";
  write_checkpoint(dir, m, blobs);
  log::debug("checkpoint at t = ", at.time, " (step ", at.step_index, ")");
  return dir / std::string(kCheckpointManifestName);
}

void restore_checkpoint(const LoadedCheckpoint& checkpoint, FluidService* fluid, SsaService* ssa) {
  auto blob = [&](const char* service) -> const std::string& {
    const auto it = checkpoint.blobs.find(service);
    if (it == checkpoint.blobs.end()) {
      throw InvalidArgument(std::string("checkpoint has no '") + service + "' blob");
    }
    return it->second.bytes;
  };
  if (fluid) fluid->restore(blob("fluid"));
  if (ssa) ssa->restore(blob("ssa"));
}

}  // namespace sadr::orchestrator
