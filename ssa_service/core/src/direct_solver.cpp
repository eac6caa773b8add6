// SPDX-License-Identifier: MIT
#include "sadr/ssa/direct_solver.hpp"

#include <cmath>
#include <string>

#include "sadr/common/status.hpp"

namespace sadr::ssa {

DirectSolver::DirectSolver(Model model, std::uint64_t seed)
    : state_(std::move(model)), rng_(seed, kStreamId) {}

double DirectSolver::total_propensity() const {
  const auto n = static_cast<std::uint32_t>(state_.voxel_count());
  const ReactionTable& rt = state_.reactions();
  const DiffusionGraph& g = state_.graph();
  const std::int64_t* x = state_.all_counts().data();
  double a0 = 0;
  for (std::uint32_t i = 0; i < n; ++i) {
    for (std::size_t r = 0; r < rt.reaction_count(); ++r) a0 += rt.propensity(r, i, x, n);
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    for (int s : state_.diffusing_species()) {
      const double kx =
          state_.model().species[s].def.diffusivity * static_cast<double>(x[s * n + i]);
      const std::uint32_t end = state_.edge_end(s, i);
      const bool filter = state_.has_free_walls(s);
      for (std::uint32_t k = g.row_start[i]; k < end; ++k) {
        if (!filter || state_.uses_edge(s, i, k)) a0 += kx * g.edges[k].weight;
      }
    }
  }
  return a0;
}

void DirectSolver::fire(double u) {
  const auto n = static_cast<std::uint32_t>(state_.voxel_count());
  const ReactionTable& rt = state_.reactions();
  const DiffusionGraph& g = state_.graph();
  const std::int64_t* x = state_.all_counts().data();
  // Last positive channel, the fallback when round-off leaves u >= the running sum.
  int last_s = -2;
  std::uint32_t last_i = 0, last_k = 0;
  std::size_t last_r = 0;
  for (std::uint32_t i = 0; i < n; ++i) {
    for (std::size_t r = 0; r < rt.reaction_count(); ++r) {
      const double p = rt.propensity(r, i, x, n);
      if (u < p) {
        state_.apply_reaction(r, i);
        return;
      }
      u -= p;
      if (p > 0) last_s = -1, last_i = i, last_r = r;
    }
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    for (int s : state_.diffusing_species()) {
      const double kx =
          state_.model().species[s].def.diffusivity * static_cast<double>(x[s * n + i]);
      if (kx == 0) continue;
      const std::uint32_t end = state_.edge_end(s, i);
      const bool filter = state_.has_free_walls(s);
      for (std::uint32_t k = g.row_start[i]; k < end; ++k) {
        if (filter && !state_.uses_edge(s, i, k)) continue;
        const double p = kx * g.edges[k].weight;
        if (u < p) {
          state_.apply_jump(s, i, g.edges[k].target);
          return;
        }
        u -= p;
        last_s = s, last_i = i, last_k = k;
      }
    }
  }
  if (last_s == -1) {
    state_.apply_reaction(last_r, last_i);
  } else if (last_s >= 0) {
    state_.apply_jump(last_s, last_i, g.edges[last_k].target);
  }
}

void DirectSolver::advance(double t_end) {
  if (!state_.has_graph()) {
    throw FailedPrecondition("DirectSolver::advance: call update_graph() first");
  }
  if (!(t_end >= time_) || !std::isfinite(t_end)) {
    throw InvalidArgument("advance: t_end = " + format_value(t_end) +
                          " (allowed: finite and >= current time " + format_value(time_) + ")");
  }
  state_.apply_reservoirs();
  for (;;) {
    const double a0 = total_propensity();
    if (!(a0 > 0)) break;
    const double t = time_ + rng_.exponential() / a0;
    if (t > t_end) break;  // memoryless: discarding the overshooting draw is exact
    time_ = t;
    fire(rng_.uniform() * a0);
    ++events_;
  }
  time_ = t_end;
}

}  // namespace sadr::ssa
