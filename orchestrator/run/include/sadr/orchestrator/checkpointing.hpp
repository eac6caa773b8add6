// SPDX-License-Identifier: MIT
/// \file checkpointing.hpp
/// Checkpoints of one realization: both services' snapshots written as a
/// checkpoint directory (checkpoint.hpp), and restored from one on resume.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "sadr/orchestrator/checkpoint.hpp"
#include "sadr/orchestrator/scene.hpp"
#include "sadr/orchestrator/service_interfaces.hpp"

namespace sadr::orchestrator {

/// Where a checkpoint comes from: the run and the point it reached.
struct CheckpointPoint {
  std::uint64_t seed = 0;  ///< realization seed
  std::uint64_t realization = 0;
  std::uint64_t step_index = 0;  ///< coupling steps completed
  double time = 0.0;             ///< [time]
};

/// Writes output_dir/checkpoint (blobs "fluid" with the scene's backend name and
/// "ssa" for each service present, and "step_control" when `control_state` is not
/// empty: SplittingLoop::control_state()) and returns the manifest's path.
std::filesystem::path save_checkpoint(const Scene& scene, const CheckpointPoint& at,
                                      FluidService* fluid, SsaService* ssa,
                                      const std::filesystem::path& output_dir,
                                      const std::string& control_state = {});

/// Restores every service present from its blob in `checkpoint`; throws
/// InvalidArgument naming the missing blob.
void restore_checkpoint(const LoadedCheckpoint& checkpoint, FluidService* fluid, SsaService* ssa);

}  // namespace sadr::orchestrator
