// SPDX-License-Identifier: MIT
/// \file adaptive_leap.hpp
/// The leaping half of the adaptive SSA (Model::method == kAdaptive; docs/method.md
/// "Adaptive SSA"). NsmSolver::advance() cuts [t, t_end] into windows; at each window start
///  - classify(): a (species s, voxel i) pair is *abundant* when s diffuses out of i
///    (kappa_s W_si > 0, i open or a reservoir of s) and X_si >= n_c = max(10, ceil(1/eps));
///  - window(): tau = the largest step with, for every abundant pair, a_si tau <= eps
///    (a_si = kappa_s W_si, the per-molecule jump rate out of i) and the Cao-Gillespie-Petzold
///    bounds |mu_si| tau <= max(eps X_si, 1), sigma2_si tau <= max(eps X_si, 1)^2 on the
///    expected change of X_si (diffusion in and out, and every reaction);
///  - leap(), at the window's midpoint: each abundant open pair sends
///    K ~ Binomial(X_si, a_si tau) molecules out of i (a_si tau <= eps), a reservoir pair
///    emits K ~ Poisson(X_si a_si tau) (its count is held), split over the usable out-edges
///    by conditional binomials with probabilities d_ij / W_si (jumps into a reservoir are
///    absorbed). K <= X_si and arrivals only add, so no count becomes negative. The window's
///    exact NSM runs on both halves without those pairs' diffusion (RdmeState::fire_masked()).
/// NsmSolver::advance() leaps a window only when jump_rate() tau exceeds the window's
/// O(N + E) bookkeeping (src/nsm_adaptive.cpp).
/// Its random numbers come from their own stream (seed, kStreamId), so the NSM's stream is
/// the exact solver's: with no abundant pair the run is the exact NSM's, event for event.
#pragma once

#include <cstdint>
#include <vector>

#include "sadr/common/rng.hpp"
#include "sadr/ssa/rdme_state.hpp"

namespace sadr::ssa {

class AdaptiveLeap {
 public:
  /// Stream id of the leaps within a realization's seed.
  static constexpr std::uint64_t kStreamId = 0x55A1;

  /// @param tolerance eps, 0 < eps < 1 (Model::validate checks it)
  AdaptiveLeap(double tolerance, std::uint64_t seed);

  [[nodiscard]] double tolerance() const { return eps_; }
  /// n_c: the smallest count whose diffusion is leaped.
  [[nodiscard]] std::int64_t critical_count() const { return n_c_; }

  /// Marks the abundant pairs of `state` (mask()); @return whether there is one.
  bool classify(const RdmeState& state);
  /// One byte per (species, voxel), species-major: 1 = leaped in this window.
  [[nodiscard]] const std::uint8_t* mask() const { return mask_.data(); }
  /// The window length tau [T] for the pairs of the last classify() (> 0; +inf when
  /// nothing limits it).
  [[nodiscard]] double window(const RdmeState& state);
  /// The exact events per unit time a window of the last window() call saves: the total
  /// diffusion propensity of the abundant pairs [1/T].
  [[nodiscard]] double jump_rate() const { return jump_rate_; }
  /// Leaps the diffusion of the pairs of the last classify() over tau.
  /// @return the molecules moved (absorbed ones included).
  std::uint64_t leap(RdmeState& state, double tau);

  /// Molecules moved by leaps since construction (or the restored value).
  [[nodiscard]] std::uint64_t moved() const { return moved_; }
  [[nodiscard]] const rng::Xoshiro256::State& rng_state() const { return rng_.state(); }
  /// Snapshot restore: the stream and the counter.
  void restore(const rng::Xoshiro256::State& state, std::uint64_t moved) {
    rng_.set_state(state);
    moved_ = moved;
  }

 private:
  double eps_;
  std::int64_t n_c_;
  rng::Xoshiro256 rng_;
  std::uint64_t moved_ = 0;
  double jump_rate_ = 0;
  std::vector<std::uint8_t> mask_;
  std::vector<double> flow_in_;        ///< scratch: expected arrivals per voxel [1/T]
  std::vector<std::int64_t> start_;    ///< scratch: X_s at the window start
  std::vector<std::uint32_t> usable_;  ///< scratch: usable out-edges of one row
};

}  // namespace sadr::ssa
