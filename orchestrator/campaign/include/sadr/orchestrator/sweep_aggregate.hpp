// SPDX-License-Identifier: MIT
/// \file sweep_aggregate.hpp
/// Per-point ensemble statistics of a sweep (docs/sweeps.md): for every frame
/// and particle, the mean, unbiased variance, standard error and 95 %
/// confidence interval (Student t) of every species, and of velocity and
/// density where they differ between realizations; as CSV and as VTK (.vtu
/// frames and a .pvd). Streaming: the runs are read one after the other, in
/// realization order (Welford), so memory does not grow with R and the files
/// do not depend on the order in which runs finished.
#pragma once

#include <cstddef>
#include <filesystem>
#include <ostream>
#include <span>
#include <string>
#include <vector>

#include "sadr/orchestrator/scene.hpp"

namespace sadr::orchestrator {

struct PointAggregate {
  std::size_t realizations = 0;
  std::size_t frames = 0;
  /// Positions equal in every realization at every frame (else the .vtu
  /// files carry realization 0's positions).
  bool positions_identical = true;
  /// vx, vy, vz and density were aggregated (they differ between realizations).
  bool fluid_columns = false;
  std::vector<std::string> notes;
};

/// The scene's named observables (output.observables), with their regions,
/// ready for aggregate_point.
struct NamedObservables {
  std::vector<ObservableSpec> specs;
  std::vector<Region> regions;  ///< one per spec; membership is recomputed per frame
  int dimension = 3;
  double tolerance = 0;  ///< region boundary tolerance [length], as the scene loader's
};
NamedObservables named_observables(const Scene& scene);

/// Aggregates the CSV frames of `runs` (run directories, realization order)
/// into `out` (frame_NNNNNN.csv, frame_NNNNNN.vtu, `name`.pvd). Every run
/// must have the same frames as the first one, with the same particles.
/// For each run and frame, appends the species totals to `observables` as
/// tidy rows "<prefix of the run>,frame,time,species,total", then one row per
/// named observable "<prefix>,frame,time,<observable name>,<value>", its
/// region's particles taken at that frame's positions (a mean over a region
/// that holds no particle at a frame is refused, naming both).
/// @param prefixes one CSV prefix per run (e.g. "0,2,0.1" for point, realization, value)
/// @throws sadr::InvalidArgument naming the run and frame that do not fit.
PointAggregate aggregate_point(std::span<const std::filesystem::path> runs,
                               std::span<const std::string> prefixes,
                               const std::filesystem::path& out, const std::string& name,
                               std::ostream& observables, const NamedObservables& named = {});

/// The two-sided 95 % Student t quantile for `n` samples (n - 1 degrees of
/// freedom): mean +- t sem is the 95 % confidence interval. NaN for n < 2.
double t95(std::size_t n);

}  // namespace sadr::orchestrator
