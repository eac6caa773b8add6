// SPDX-License-Identifier: MIT
/// \file ensemble_accumulator.hpp
/// Per-frame, per-particle mean and unbiased variance of every species over
/// independent realizations (Welford's update; Chan et al.'s pairwise merge
/// for accumulators filled by different threads).
#pragma once

#include <cstddef>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "sadr/orchestrator/frame_writers.hpp"

namespace sadr::orchestrator {

class EnsembleAccumulator {
 public:
  /// @param species names of the accumulated species (columns of every frame)
  /// @param particle_count N, the number of particles in every frame
  EnsembleAccumulator(std::vector<std::string> species, std::size_t particle_count);

  /// Adds one realization's values at frame `frame` (0-based output index).
  /// `columns` must hold every accumulated species with N values (extra
  /// columns are ignored). @param time frame time [time]; must agree with
  /// earlier additions to the same frame.
  /// @throws sadr::InvalidArgument on a missing species, wrong length or time.
  void add(std::size_t frame, double time, std::span<const SpeciesColumn> columns);

  /// Combines another accumulator over the same species and N into this one.
  void merge(const EnsembleAccumulator& other);

  [[nodiscard]] std::size_t frame_count() const { return frames_.size(); }
  /// Realizations added to `frame` (0 if none).
  [[nodiscard]] std::size_t realizations(std::size_t frame) const;
  [[nodiscard]] double time(std::size_t frame) const { return frames_.at(frame).time; }
  [[nodiscard]] double mean(std::size_t frame, std::size_t species, std::size_t particle) const;
  /// Unbiased sample variance (divides by n - 1); NaN with fewer than 2 realizations.
  [[nodiscard]] double variance(std::size_t frame, std::size_t species, std::size_t particle) const;
  [[nodiscard]] const std::vector<std::string>& species() const { return species_; }

  /// Writes frame `frame` as CSV with columns
  /// time,id,realizations,<s>_mean,<s>_var,... ("%.17g"; ids are 0..N-1
  /// unless `ids` gives N particle ids).
  void write_csv(std::size_t frame, const std::filesystem::path& path,
                 std::span<const std::uint64_t> ids = {}) const;

 private:
  struct Frame {
    double time = 0.0;
    std::size_t count = 0;
    std::vector<double> mean;  ///< species-major: [s * N + i]
    std::vector<double> m2;    ///< sum of squared deviations
  };
  Frame& frame_at(std::size_t frame, double time);

  std::vector<std::string> species_;
  std::size_t n_;
  std::vector<Frame> frames_;
};

}  // namespace sadr::orchestrator
