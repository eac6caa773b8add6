// SPDX-License-Identifier: MIT
// The exact channels of the adaptive SSA: RdmeState::total_rate_masked() and fire_masked(),
// total_rate() and fire() without the diffusion of the leaped (species, voxel) pairs
// (adaptive_leap.hpp). Same channel order and arithmetic as fire(), so with no pair
// leaped they pick the same channel from the same uniform. The exact NSM never calls them.
#include <limits>
#include <string>

#include "sadr/common/status.hpp"
#include "sadr/ssa/rdme_state.hpp"

namespace sadr::ssa {

double RdmeState::total_rate_masked(std::uint32_t i, const std::uint8_t* leaped) const {
  double a = 0;
  for (int s : diffusing_) {
    if (leaped[static_cast<std::size_t>(s) * n_ + i]) continue;
    a += kappa_[s] * static_cast<double>(counts_[s * n_ + i]) * jump_weight_sum(s, i);
  }
  return reaction_rate(i) + a;
}

std::uint32_t RdmeState::fire_masked(std::uint32_t i, double u, const std::uint8_t* leaped) {
  int last_kind = -1;  // 0 reaction, 1 diffusion: the round-off fallback as in fire()
  std::size_t last_index = 0;
  if (voxels_[i].active) {
    for (std::size_t r = 0; r < table_.reaction_count(); ++r) {
      const double p = reaction_propensity(r, i);
      if (u < p) {
        apply_reaction(r, i);
        return kNoVoxel;
      }
      u -= p;
      if (p > 0) last_kind = 0, last_index = r;
    }
  }
  for (int s : diffusing_) {
    if (leaped[static_cast<std::size_t>(s) * n_ + i]) continue;
    const std::int64_t x = counts_[s * n_ + i];
    if (x == 0) continue;
    const double per_weight = kappa_[s] * static_cast<double>(x);
    const double p = per_weight * jump_weight_sum(s, i);
    if (p <= 0) continue;
    if (u < p) {
      double v = u / per_weight;
      if (has_free_walls(s)) return apply_jump(s, i, graph_.edges[free_edge(s, i, v)].target);
      const std::uint32_t end = edge_end(s, i);
      std::uint32_t k = voxels_[i].begin;
      for (; k + 1 < end; ++k) {
        v -= graph_.edges[k].weight;
        if (v < 0) break;
      }
      return apply_jump(s, i, graph_.edges[k].target);
    }
    u -= p;
    last_kind = 1, last_index = static_cast<std::size_t>(s);
  }
  if (last_kind == 0) {
    apply_reaction(last_index, i);
    return kNoVoxel;
  }
  if (last_kind == 1) {
    const int s = static_cast<int>(last_index);
    if (has_free_walls(s)) {
      return apply_jump(
          s, i, graph_.edges[free_edge(s, i, std::numeric_limits<double>::infinity())].target);
    }
    return apply_jump(s, i, graph_.edges[edge_end(s, i) - 1].target);
  }
  throw Error(StatusCode::kInternal,
              "RdmeState::fire_masked: voxel " + std::to_string(i) + " has zero exact rate");
}

}  // namespace sadr::ssa
