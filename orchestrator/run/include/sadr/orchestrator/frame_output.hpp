// SPDX-License-Identifier: MIT
/// \file frame_output.hpp
/// Frames of one realization: the services' current state written as
/// .vtu/.vtp/.csv (frames/frame_NNNNNN.*), the .pvd index that lists them,
/// and the frame list of the run manifest.
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "sadr/common/rate_law.hpp"

#include "sadr/orchestrator/frame_writers.hpp"
#include "sadr/orchestrator/run_manifest.hpp"
#include "sadr/orchestrator/scene.hpp"
#include "sadr/orchestrator/service_interfaces.hpp"

namespace sadr::orchestrator {

class FrameOutput {
 public:
  /// Frames go to output_dir/frames (created), the index to
  /// output_dir/<scene name>.pvd; file names are appended to manifest.frames.
  FrameOutput(const Scene& scene, const std::filesystem::path& output_dir, RunManifest& manifest);

  /// Writes frame `index` at time t: particles and deterministic
  /// concentrations from `fluid` (or `particles` when there is none), copy
  /// numbers of stochastic output species from `ssa`. Returns the species
  /// columns written (in output order).
  std::vector<SpeciesColumn> write(std::size_t index, double t, FluidService* fluid,
                                   SsaService* ssa, const ParticleState& particles);
  /// Lists the frames at output times <= t again (written before a checkpoint
  /// the run resumes from).
  void relist_until(double t);

 private:
  void list(std::size_t index, double t);
  /// Evaluates the assigned species in output.species into `values` (their inputs
  /// are in it: concentrations, or counts of stochastic species, divided by V_i).
  void evaluate_assigned(std::map<std::string, std::vector<double>>& values,
                         const ParticleState& state);

  const Scene& scene_;
  std::filesystem::path dir_;
  RunManifest& manifest_;
  PvdCollection pvd_;
  std::vector<std::pair<std::string, rate_law::RateLaw>> assigned_;  ///< written ones
  std::vector<std::string> fluid_species_;  ///< asked of the fluid per frame
  std::vector<std::string> ssa_species_;    ///< asked of the SSA per frame
};

/// The deterministic species a frame asks the fluid for (FluidService::frame):
/// the output species, then those the assigned output species read.
std::vector<std::string> frame_fluid_species(const Scene& scene);

}  // namespace sadr::orchestrator
