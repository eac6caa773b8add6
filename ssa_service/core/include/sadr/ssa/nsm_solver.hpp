// SPDX-License-Identifier: MIT
/// \file nsm_solver.hpp
/// Exact Next Subvolume Method (Elf & Ehrenberg 2004) on the particle
/// diffusion graph (docs/method.md section 4).
///
/// Per voxel i the total rate a_i = sum_r a_ir + sum_s X_si kappa_s sum_j D_ij is
/// cached; the next event time of every voxel sits in a priority queue.
/// An event pops the earliest voxel, selects reaction / species / neighbour
/// with ONE uniform draw scaled by a_i, updates the counts, recomputes the
/// rates of the touched voxels from the counts, draws a fresh exponential for
/// the voxel that fired and rescales the time of a jump target whose rate
/// changed without firing (Gibson & Bruck 2000: tau' = t + (a/a')(tau - t)).
/// The queue is a tournament tree over the times (EventTree).
/// update_graph() rebuilds graph and rates in O(N) and rescales every pending time
/// the same way (tau' = t + (a/a')(tau - t): no random numbers, exact by the same
/// argument; a voxel idle before, a = 0, gets a fresh draw), and does nothing when
/// the particles did not change.
///
/// Random numbers: one Xoshiro256** stream, seeded from (seed, kStreamId)
/// through rng::mix_seed; its state is part of every snapshot.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sadr/common/particle_state.hpp"
#include "sadr/common/rng.hpp"
#include "sadr/ssa/adaptive_leap.hpp"
#include "sadr/ssa/event_heap.hpp"
#include "sadr/ssa/model.hpp"
#include "sadr/ssa/rdme_state.hpp"

namespace sadr::ssa {

class NsmSolver {
 public:
  /// Stream id of the NSM within a realization's seed (rng::Xoshiro256(seed, kStreamId)).
  static constexpr std::uint64_t kStreamId = 0x55A0;
  /// Snapshot format version written by save().
  /// Version 2 stores the next event times by voxel; version 1 (heap entries
  /// in heap order, the same information) is still read. Adaptive models write
  /// kAdaptiveSnapshotVersion (version 2 plus the leap stream and its counter).
  static constexpr std::uint32_t kSnapshotVersion = 2;
  static constexpr std::uint32_t kAdaptiveSnapshotVersion = 3;

  /// @param model validated here (throws InvalidArgument naming field and value)
  /// @param seed  realization seed; equal seeds give identical trajectories
  NsmSolver(Model model, std::uint64_t seed);

  /// Rebuilds graph, rates and queue in O(N) when positions, densities, masses
  /// or kinds differ from the last call (validating the particles); otherwise
  /// does nothing. Pending event times are rescaled to the new rates (Gibson-Bruck),
  /// fresh draws only for voxels whose rate was 0. The first call fixes the voxel
  /// count N (counts start at 0). Wall reservoirs are re-imposed. @return true if rebuilt.
  bool update_graph(const ParticleState& particles);
  /// Sets the copy numbers of `species` (N values >= 0); all rates recomputed
  /// and all next-event times redrawn (O(N)).
  void set_counts(int species, std::span<const std::int64_t> counts);
  /// Copy numbers of `species`, one per particle (valid until the next call
  /// that changes state).
  [[nodiscard]] std::span<const std::int64_t> counts(int species) const {
    return state_.counts(species);
  }
  /// Hybrid reactions and laws of t (docs/method.md section 4c): the rate laws that
  /// read t or a frozen species are re-evaluated at `t` and `frozen` (RdmeState::set_inputs)
  /// and held constant until the next call; pending event times are rescaled to the
  /// new rates (Gibson-Bruck: exact for piecewise-constant rates). Without such laws
  /// it does nothing (no check, no cost).
  void set_inputs(double t, std::span<const double> frozen);
  /// Runs every event with time <= t_end on the frozen graph, then sets the
  /// clock to exactly t_end (pending event times stay valid: memorylessness).
  /// Adaptive models (Model::method) go through advance_adaptive() instead.
  /// @param t_end [T], >= time()
  void advance(double t_end);

  [[nodiscard]] double time() const { return time_; }  ///< current time [T]
  /// Events fired exactly (by the NSM) so far.
  [[nodiscard]] std::uint64_t events() const { return events_; }
  /// Molecules moved by the adaptive method's leaps so far (0 for the exact NSM).
  [[nodiscard]] std::uint64_t leaped_molecules() const { return leap_ ? leap_->moved() : 0; }
  /// Windows with at least one leaped pair so far (adaptive only; not in snapshots).
  [[nodiscard]] std::uint64_t leap_windows() const { return leap_windows_; }

  /// Complete state (counts, clock, event count, event times, RNG, graph inputs) as a
  /// versioned binary blob (native little-endian; layout in docs/ssa-core.md).
  [[nodiscard]] std::string save() const;
  /// Restores a save() blob made by a solver with the same model; the run then
  /// continues bit-identically. Throws InvalidArgument on a corrupt blob,
  /// another version, or another model.
  void restore(std::string_view blob);

  [[nodiscard]] const Model& model() const { return state_.model(); }
  [[nodiscard]] const RdmeState& state() const { return state_; }
  [[nodiscard]] const DiffusionGraph& graph() const { return state_.graph(); }
  /// Cached total rate a_i of voxel i [1/T] (tests, diagnostics).
  [[nodiscard]] double voxel_rate(std::uint32_t i) const { return state_.cached_rate(i); }
  /// The event queue (next event time of every voxel).
  [[nodiscard]] const EventTree& queue() const { return queue_; }

 private:
  /// All rates from the counts, fresh exponential times from time_, queue rebuilt.
  void rebuild_queue();
  /// All rates from the counts; each pending time rescaled from the cached (old)
  /// rate to the new one, a fresh draw where the old rate was 0; queue rebuilt. With
  /// `leaped` (the adaptive method), the rates leave out the diffusion of the pairs it marks.
  void rescale_queue(const std::uint8_t* leaped = nullptr);
  /// advance() of the adaptive method (nsm_adaptive.cpp, adaptive_leap.hpp).
  void advance_adaptive(double t_end);
  /// Fires the events with time <= t_w under `leaped` (nullptr: the exact channels), at
  /// most `budget` of them. @return the time of the last event if the budget ended the
  /// loop, else t_w.
  double run_window(double t_w, const std::uint8_t* leaped, std::uint64_t budget);

  RdmeState state_;
  EventTree queue_;
  rng::Xoshiro256 rng_;
  std::uint64_t seed_;
  double time_ = 0;
  std::uint64_t events_ = 0;
  std::vector<double> times_scratch_;  ///< rebuild/rescale: new times by voxel
  std::optional<AdaptiveLeap> leap_;   ///< adaptive models only
  std::uint64_t leap_windows_ = 0;
};

}  // namespace sadr::ssa
