// SPDX-License-Identifier: MIT
#include "sadr/ssa/nsm_solver.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "exponential.hpp"
#include "sadr/common/status.hpp"

namespace sadr::ssa {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}

NsmSolver::NsmSolver(Model model, std::uint64_t seed)
    : state_(std::move(model)), rng_(seed, kStreamId), seed_(seed) {
  if (state_.model().method == SsaMethod::kAdaptive) {
    leap_.emplace(state_.model().tolerance, seed);
  }
}

bool NsmSolver::update_graph(const ParticleState& particles) {
  // The queue of the previous graph (same voxels) keeps its pending draws.
  const bool rescale = state_.has_graph() && queue_.size() == state_.voxel_count();
  if (!state_.update_graph(particles)) return false;
  if (rescale && queue_.size() == state_.voxel_count()) {
    rescale_queue();
  } else {
    rebuild_queue();
  }
  return true;
}

void NsmSolver::set_counts(int species, std::span<const std::int64_t> counts) {
  state_.set_counts(species, counts);
  rebuild_queue();
}

void NsmSolver::set_inputs(double t, std::span<const double> frozen) {
  if (!state_.reactions().has_external_laws()) return;
  if (!state_.has_graph()) {
    throw FailedPrecondition("NsmSolver::set_inputs: call update_graph() first");
  }
  state_.set_inputs(t, frozen);
  if (queue_.size() == state_.voxel_count()) {
    rescale_queue();
  } else {
    rebuild_queue();
  }
}

void NsmSolver::rebuild_queue() {
  const std::size_t n = state_.voxel_count();
  std::vector<double>& times = times_scratch_;
  times.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double a = state_.total_rate(static_cast<std::uint32_t>(i));
    state_.cached_rate(static_cast<std::uint32_t>(i)) = a;
    times[i] = a > 0 ? time_ + detail::exponential(rng_) / a : kInf;
  }
  queue_.assign(times);
}

void NsmSolver::rescale_queue(const std::uint8_t* leaped) {
  // Gibson & Bruck 2000: given the history, tau - t of a voxel that has not fired is
  // Exp(a_old); (a_old / a_new)(tau - t) is then Exp(a_new), so the pending draw is
  // reused. The cached rates are still those of the old graph (RdmeState::update_graph
  // keeps them); they equal total_rate() of the old graph and counts, also after a
  // restore (which recomputes them), so a restored run rescales identically.
  const std::size_t n = state_.voxel_count();
  std::vector<double>& times = times_scratch_;
  times.resize(n);
  const double t = time_;
  for (std::size_t i = 0; i < n; ++i) {
    const auto v = static_cast<std::uint32_t>(i);
    const double a_old = state_.cached_rate(v);
    const double a_new = leaped ? state_.total_rate_masked(v, leaped) : state_.total_rate(v);
    state_.cached_rate(v) = a_new;
    const double tau = queue_.time_of(v);
    double ti = kInf;
    if (a_new > 0) {
      if (a_old == a_new) {
        ti = tau;
      } else if (a_old > 0 && tau < kInf) {
        ti = t + (a_old / a_new) * (tau - t);
      } else {
        ti = t + detail::exponential(rng_) / a_new;  // idle before: a fresh draw
      }
    }
    times[i] = ti;
  }
  queue_.assign(times);
}

void NsmSolver::advance(double t_end) {
  if (!state_.has_graph()) {
    throw FailedPrecondition("NsmSolver::advance: call update_graph() first");
  }
  if (!(t_end >= time_) || !std::isfinite(t_end)) {
    throw InvalidArgument("advance: t_end = " + format_value(t_end) +
                              " (allowed: finite and >= current time " + format_value(time_) + ")",
                          {{"field", "t_end"}, {"value", format_value(t_end)}});
  }
  if (leap_) {
    advance_adaptive(t_end);
    return;
  }
  if (state_.apply_reservoirs()) rebuild_queue();
  if (queue_.empty()) {
    time_ = t_end;
    return;
  }
  std::uint64_t fired = 0;
  for (;;) {
    const double t = queue_.top_time();
    if (!(t <= t_end)) break;
    const std::uint32_t i = queue_.top_voxel();
    const std::uint32_t j = state_.fire(i, rng_.uniform() * state_.cached_rate(i));
    ++fired;
    // The jump target's record and time are needed below: start loading them now,
    // so that the misses overlap with the fired voxel's rate and tree update.
    if (j != kNoVoxel) {
      state_.prefetch_target(j);
      queue_.prefetch(j);
    }
    const double ai = state_.total_rate(i);
    state_.cached_rate(i) = ai;
    queue_.update_top(ai > 0 ? t + detail::exponential(rng_) / ai : kInf);
    // Memory-level parallelism: the top now is the next event's voxel unless j
    // overtakes it (rare). Its record, counts and time were requested one event
    // ago (as the runner-up, below); the record gives its edge row's address.
    const std::uint32_t next = queue_.top_voxel();
    state_.prefetch(next);
    // Two events ahead: the runner-up is the event after next unless next's new
    // time or a jump target's overtakes it (99.99 % of the events of ssa_bench a);
    // a full event of lead time for its record, counts and time.
    const std::uint32_t after = queue_.runner_up();
    state_.prefetch_record(after);
    queue_.prefetch(after);
    if (j != kNoVoxel) {
      const double a_old = state_.cached_rate(j);
      const double a_new = state_.total_rate(j);
      state_.cached_rate(j) = a_new;
      double tj = kInf;
      if (a_new > 0) {
        const double tau = queue_.time_of(j);
        // Gibson-Bruck rescaling reuses the pending draw; a voxel that was
        // idle (a_old = 0, tau = inf) gets a fresh one.
        tj = (a_old > 0 && tau < kInf) ? t + (a_old / a_new) * (tau - t)
                                       : t + detail::exponential(rng_) / a_new;
      }
      queue_.update(j, tj);
    }
  }
  events_ += fired;
  time_ = t_end;
}

}  // namespace sadr::ssa
