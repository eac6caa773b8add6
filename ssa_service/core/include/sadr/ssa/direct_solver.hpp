// SPDX-License-Identifier: MIT
/// \file direct_solver.hpp
/// Baseline: the seed paper's algorithm (drawert2019 Algorithms 1-2): Gillespie's
/// direct method with a LINEAR SEARCH over every propensity of the system at
/// every event: all reaction channels (voxel x reaction) first, then all
/// diffusion channels (voxel x species x neighbour). O(N * neighbours * S) per
/// event. Written correctly (full propensities, recomputed from the counts
/// after each event, A + B with k/V), it samples exactly the same process as
/// NsmSolver, so it serves as a cross-check and as the benchmark baseline.
/// Not for production use.
#pragma once

#include <cstdint>
#include <span>

#include "sadr/common/particle_state.hpp"
#include "sadr/common/rng.hpp"
#include "sadr/ssa/model.hpp"
#include "sadr/ssa/rdme_state.hpp"

namespace sadr::ssa {

class DirectSolver {
 public:
  static constexpr std::uint64_t kStreamId = 0xD1EC7;

  DirectSolver(Model model, std::uint64_t seed);
  /// As NsmSolver::update_graph (no queue to rebuild). @return true if rebuilt.
  bool update_graph(const ParticleState& particles) { return state_.update_graph(particles); }
  void set_counts(int species, std::span<const std::int64_t> counts) {
    state_.set_counts(species, counts);
  }
  [[nodiscard]] std::span<const std::int64_t> counts(int species) const {
    return state_.counts(species);
  }
  /// Direct-method steps until the next event would pass t_end; clock = t_end.
  void advance(double t_end);
  [[nodiscard]] double time() const { return time_; }
  [[nodiscard]] std::uint64_t events() const { return events_; }
  [[nodiscard]] const RdmeState& state() const { return state_; }

 private:
  /// Sum of every channel's propensity, computed channel by channel [1/T].
  double total_propensity() const;
  /// Fires the channel where the running sum first exceeds u.
  void fire(double u);

  RdmeState state_;
  rng::Xoshiro256 rng_;
  double time_ = 0;
  std::uint64_t events_ = 0;
};

}  // namespace sadr::ssa
