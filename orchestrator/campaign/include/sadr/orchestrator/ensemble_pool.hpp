// SPDX-License-Identifier: MIT
/// \file ensemble_pool.hpp
/// The realizations of `sadr run -r R` on `jobs` threads: each realization is
/// a function the caller passes in (it runs the services); their frames are
/// added to the ensemble in index order (reorder_buffer.hpp), whatever order
/// they finish in.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "sadr/orchestrator/ensemble_accumulator.hpp"
#include "sadr/orchestrator/ensemble_manifest.hpp"

namespace sadr::orchestrator {

/// The frames of one realization: frame index -> (time, species columns).
using RealizationFrames = std::map<std::size_t, std::pair<double, std::vector<SpeciesColumn>>>;

/// What one realization of the pool ended with.
struct MemberResult {
  std::optional<FailedRealization> failure;  ///< set: it failed (after its retries)
  bool interrupted = false;                  ///< stopped early: its frames are not added
  RealizationFrames frames;
};

struct PoolResult {
  std::vector<FailedRealization> failed;  ///< by realization index
  int done = 0;                           ///< realizations that did not fail
};

/// Runs `member(r)` for r = 0..count-1 on `jobs` threads, each taking the next
/// index until all are taken or `interrupt` is set, and adds the frames of
/// the realizations that ended to `ensemble` in index order (a failed one adds
/// nothing; an interrupted one stops the adding there). Prints a line per failed realization and,
/// unless `quiet`, per realization done with the elapsed time and an estimate of the rest.
PoolResult run_ensemble_pool(EnsembleAccumulator& ensemble, int count, int jobs, bool quiet,
                             const std::atomic<bool>& interrupt,
                             const std::function<MemberResult(int)>& member);

/// Writes DIR/ensemble/frame_KKKKKK.csv for every frame with at least one realization.
void write_ensemble_frames(const EnsembleAccumulator& ensemble, const std::filesystem::path& dir,
                           std::span<const std::uint64_t> ids);

}  // namespace sadr::orchestrator
