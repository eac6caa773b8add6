// SPDX-License-Identifier: MIT
// NsmSolver::advance() of the adaptive SSA (Model::method == kAdaptive; adaptive_leap.hpp,
// docs/method.md "Adaptive SSA"). [time, t_end] is cut into windows. At each window start the
// abundant (species, voxel) pairs are classified from the counts:
//  - some pair abundant: tau from the tolerance (AdaptiveLeap::window), the window ends at
//    min(t + tau, t_end); the NSM fires every other channel exactly over the window with
//    those pairs masked out, and the abundant pairs' diffusion is leaped at its midpoint;
//  - none abundant, or a leaping window would save fewer exact events than its O(N + E)
//    bookkeeping costs: the exact NSM runs unmasked until t_end or until a budget of events
//    (4 per (species, voxel), at least 4096) has fired, when the counts are classified again.
// Every change of the exact rates (a leap, a new mask) rescales the pending event times
// (Gibson-Bruck, as update_graph() does): exact for piecewise-constant rates. The NSM draws
// from its own stream in the exact solver's order, so with no abundant pair the run fires
// exactly the exact NSM's events. At t_end the mask is dropped (the rates become the exact
// ones again), so between advances the solver is an exact NSM: update_graph(), set_inputs()
// and snapshots need no window state.
#include <algorithm>
#include <cmath>
#include <limits>

#include "exponential.hpp"
#include "sadr/ssa/nsm_solver.hpp"

namespace sadr::ssa {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}

double NsmSolver::run_window(double t_w, const std::uint8_t* leaped, std::uint64_t budget) {
  // The exact loop of advance() without its prefetches; the same draws in the same order.
  std::uint64_t fired = 0;
  double last = t_w;
  for (;;) {
    const double t = queue_.top_time();
    if (!(t <= t_w)) break;
    const std::uint32_t i = queue_.top_voxel();
    const double u = rng_.uniform() * state_.cached_rate(i);
    const std::uint32_t j = leaped ? state_.fire_masked(i, u, leaped) : state_.fire(i, u);
    ++fired;
    const double ai = leaped ? state_.total_rate_masked(i, leaped) : state_.total_rate(i);
    state_.cached_rate(i) = ai;
    queue_.update_top(ai > 0 ? t + detail::exponential(rng_) / ai : kInf);
    if (j != kNoVoxel) {
      const double a_old = state_.cached_rate(j);
      const double a_new = leaped ? state_.total_rate_masked(j, leaped) : state_.total_rate(j);
      state_.cached_rate(j) = a_new;
      double tj = kInf;
      if (a_new > 0) {
        const double tau = queue_.time_of(j);
        tj = (a_old > 0 && tau < kInf) ? t + (a_old / a_new) * (tau - t)
                                       : t + detail::exponential(rng_) / a_new;
      }
      queue_.update(j, tj);
    }
    if (fired >= budget) {
      last = t;
      break;
    }
  }
  events_ += fired;
  return last;
}

void NsmSolver::advance_adaptive(double t_end) {
  if (state_.apply_reservoirs()) rebuild_queue();
  if (queue_.empty()) {
    time_ = t_end;
    return;
  }
  const std::size_t pairs =
      state_.voxel_count() * static_cast<std::size_t>(std::max(1, state_.species_count()));
  const std::uint64_t budget = std::max<std::uint64_t>(4096, 4 * pairs);
  constexpr std::uint64_t kNoBudget = std::numeric_limits<std::uint64_t>::max();
  bool masked = false;  // the cached rates are masked ones
  // A leaping window costs O(N + E) per diffusing species (classification, window length,
  // two rescales) whatever it saves: it is taken only when the exact events it replaces
  // (the abundant pairs' jump rate times its length) outnumber that; else the window is exact.
  const double overhead =
      static_cast<double>(state_.voxel_count() + state_.graph().edge_count()) *
      static_cast<double>(std::max<std::size_t>(1, state_.diffusing_species().size()));
  while (time_ < t_end) {
    double t_w = t_end;
    bool leaps = leap_->classify(state_);
    if (leaps) {
      const double tau = leap_->window(state_);
      if (time_ + tau < t_end) t_w = time_ + tau;
      if (!(t_w > time_)) t_w = std::min(t_end, std::nextafter(time_, kInf));
      leaps = leap_->jump_rate() * (t_w - time_) > overhead;
    }
    if (leaps) {
      // The leap sits at the window's midpoint (the exact channels run on both halves):
      // the leaped molecules move, on average, when they would have (docs/method.md).
      const double t0 = time_;
      const double t_mid = t0 + 0.5 * (t_w - t0);
      rescale_queue(leap_->mask());
      masked = true;
      run_window(t_mid, leap_->mask(), kNoBudget);
      time_ = t_mid;
      leap_->leap(state_, t_w - t0);
      ++leap_windows_;
      rescale_queue(leap_->mask());
      run_window(t_w, leap_->mask(), kNoBudget);
      time_ = t_w;
    } else {
      if (masked) rescale_queue(nullptr);
      masked = false;
      time_ = run_window(t_end, nullptr, budget);
    }
  }
  if (masked) rescale_queue(nullptr);  // between advances the rates are the exact ones
  time_ = t_end;
}

}  // namespace sadr::ssa
