// SPDX-License-Identifier: MIT
// Event firing: RdmeState::fire() and its no-wall fast path.
#include <cmath>
#include <limits>
#include <string>

#include "sadr/common/status.hpp"
#include "sadr/ssa/rdme_state.hpp"

namespace sadr::ssa {

namespace {
constexpr double kInfinity = std::numeric_limits<double>::infinity();
}  // namespace

std::uint32_t RdmeState::fire_open(std::uint32_t i, double u) {
  // No wall particles: every voxel is open for every species, so there are no
  // reservoirs (fixed() is false), no free-wall skips, and every species uses the
  // whole row with weight sum sum_all. Same channel order and the same arithmetic
  // as fire(), hence the same trajectory; fewer branches and loads per event.
  const VoxelRecord& v = voxels_[i];
  int last_kind = -1;  // 0 reaction, 1 diffusion (round-off fallback as in fire())
  std::size_t last_index = 0;
  if (v.active) {
    for (std::size_t r = 0; r < table_.reaction_count(); ++r) {
      const double p = reaction_propensity(r, i);
      if (u < p) {
        apply_reaction_open(r, i);
        return kNoVoxel;
      }
      u -= p;
      if (p > 0) last_kind = 0, last_index = r;
    }
  }
  std::int64_t* counts = counts_.data();
  const DiffusionGraph::Edge* edges = graph_.edges.data();
  for (int s : diffusing_) {
    std::int64_t* xs = counts + static_cast<std::size_t>(s) * n_;
    const std::int64_t x = xs[i];
    if (x == 0) continue;
    const double per_weight = kappa_[s] * static_cast<double>(x);
    const double p = per_weight * v.sum_all;
    if (p <= 0) continue;
    if (u < p) {
      double w = u / per_weight;  // the residual of the same uniform picks the edge
      std::uint32_t k = v.begin;
      for (; k + 1 < v.end; ++k) {
        w -= edges[k].weight;
        if (w < 0) break;
      }
      const std::uint32_t j = edges[k].target;
      --xs[i];
      ++xs[j];
      refresh_laws(s, i);
      refresh_laws(s, j);
      return j;
    }
    u -= p;
    last_kind = 1, last_index = static_cast<std::size_t>(s);
  }
  if (last_kind == 0) {
    apply_reaction_open(last_index, i);
    return kNoVoxel;
  }
  if (last_kind == 1) {
    std::int64_t* xs = counts + last_index * n_;
    const std::uint32_t j = edges[v.end - 1].target;
    --xs[i];
    ++xs[j];
    refresh_laws(static_cast<int>(last_index), i);
    refresh_laws(static_cast<int>(last_index), j);
    return j;
  }
  throw Error(StatusCode::kInternal,
              "RdmeState::fire: voxel " + std::to_string(i) + " has zero total rate");
}

std::uint32_t RdmeState::free_edge(int s, std::uint32_t i, double v) const {
  // The usable out-edge where the cumulative weight first exceeds v; the last
  // usable one when round-off leaves v beyond the sum.
  std::uint32_t last = kNoVoxel;
  for (std::uint32_t k = voxels_[i].begin; k < voxels_[i].end; ++k) {
    if (!uses_edge(s, i, k)) continue;
    last = k;
    v -= graph_.edges[k].weight;
    if (v < 0) break;
  }
  if (last == kNoVoxel) {
    throw Error(StatusCode::kInternal, "RdmeState::fire: voxel " + std::to_string(i) +
                                           " has no usable edge for species " + std::to_string(s));
  }
  return last;
}

std::uint32_t RdmeState::fire(std::uint32_t i, double u) {
  if (!has_walls_) return fire_open(i, u);
  // Last channel with a positive propensity: the fallback when round-off puts
  // u at or beyond the recomputed sum.
  int last_kind = -1;  // 0 reaction, 1 diffusion
  std::size_t last_index = 0;
  double last_p = 0;
  if (voxels_[i].active) {
    for (std::size_t r = 0; r < table_.reaction_count(); ++r) {
      const double p = reaction_propensity(r, i);
      if (u < p) {
        apply_reaction(r, i);
        return kNoVoxel;
      }
      u -= p;
      if (p > 0) last_kind = 0, last_index = r, last_p = p;
    }
  }
  for (int s : diffusing_) {
    const std::int64_t x = counts_[s * n_ + i];
    if (x == 0) continue;
    const double per_weight = kappa_[s] * static_cast<double>(x);
    const double p = per_weight * jump_weight_sum(s, i);
    if (p <= 0) continue;
    if (u < p) {
      // Neighbour by the cumulative weights: the residual of the same uniform.
      double v = u / per_weight;
      const std::uint32_t end = edge_end(s, i);
      std::uint32_t k = voxels_[i].begin;
      if (has_free_walls(s)) return apply_jump(s, i, graph_.edges[free_edge(s, i, v)].target);
      for (; k + 1 < end; ++k) {
        v -= graph_.edges[k].weight;
        if (v < 0) break;
      }
      return apply_jump(s, i, graph_.edges[k].target);
    }
    u -= p;
    last_kind = 1, last_index = static_cast<std::size_t>(s), last_p = p;
  }
  if (last_kind == 0) {
    apply_reaction(last_index, i);
    return kNoVoxel;
  }
  if (last_kind == 1) {
    const int s = static_cast<int>(last_index);
    if (has_free_walls(s)) {
      return apply_jump(s, i, graph_.edges[free_edge(s, i, kInfinity)].target);
    }
    const std::uint32_t end = edge_end(s, i);
    return apply_jump(s, i, graph_.edges[end - 1].target);
  }
  (void)last_p;
  throw Error(StatusCode::kInternal,
              "RdmeState::fire: voxel " + std::to_string(i) + " has zero total rate");
}

}  // namespace sadr::ssa
