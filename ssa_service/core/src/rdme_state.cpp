// SPDX-License-Identifier: MIT
#include "sadr/ssa/rdme_state.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "sadr/common/status.hpp"

namespace sadr::ssa {

RdmeState::RdmeState(Model model) : model_(std::move(model)) {
  model_.validate();
  const std::size_t ns = model_.species.size();
  kappa_.resize(ns);
  reservoir_.assign(ns, 0);
  for (std::size_t s = 0; s < ns; ++s) {
    kappa_[s] = model_.species[s].diffusivity;
    if (kappa_[s] > 0) diffusing_.push_back(static_cast<int>(s));
  }
  for (const WallReservoir& w : model_.reservoirs) reservoir_[w.species] = 1;
}

namespace {
bool same_inputs(const ParticleState& a, const ParticleState& b) {
  if (a.size() != b.size() || a.dimension != b.dimension) return false;
  if (a.positions != b.positions || a.densities != b.densities || a.masses != b.masses) {
    return false;
  }
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a.kind(i) != b.kind(i)) return false;
  }
  return true;
}
}  // namespace

bool RdmeState::update_graph(const ParticleState& particles) {
  // Unchanged particles: nothing to do (reservoir counts cannot have drifted: only
  // set_counts() writes them, and it re-imposes them itself).
  if (has_graph() && same_inputs(particles, inputs_)) return false;
  if (has_graph() && particles.size() != n_) {
    throw InvalidArgument("update_graph: particle count changed from " + std::to_string(n_) +
                              " to " + std::to_string(particles.size()) +
                              " (voxels must persist; build a new solver)",
                          {{"field", "particles"}, {"value", std::to_string(particles.size())}});
  }
  DiffusionGraph g = DiffusionGraph::build(model_, particles);  // validates
  table_ = ReactionTable::build(model_, g);
  graph_ = std::move(g);
  n_ = graph_.size();
  voxels_.assign(n_, VoxelRecord{});
  for (std::size_t i = 0; i < n_; ++i) {
    VoxelRecord& v = voxels_[i];
    v.sum_all = graph_.sum_all[i];
    v.begin = graph_.row_start[i];
    v.split = graph_.split[i];
    v.end = graph_.row_start[i + 1];
    v.is_wall = graph_.is_wall[i];
    v.active = table_.active(static_cast<std::uint32_t>(i)) ? 1 : 0;
  }
  has_walls_ = std::any_of(graph_.is_wall.begin(), graph_.is_wall.end(),
                           [](std::uint8_t w) { return w != 0; });
  inputs_.dimension = particles.dimension;
  inputs_.positions = particles.positions;
  inputs_.densities = particles.densities;
  inputs_.masses = particles.masses;
  inputs_.kinds = graph_.kind;
  if (counts_.empty()) counts_.assign(model_.species.size() * n_, 0);
  assign_reservoir_concentrations();
  apply_reservoirs();
  return true;
}

void RdmeState::assign_reservoir_concentrations() {
  reservoir_conc_.assign(model_.species.size() * n_, 0.0);
  // Precedence: a reservoir listing the wall in `voxels`, else an all-walls one, else 0.
  std::vector<std::uint8_t> explicit_set(reservoir_conc_.size(), 0);
  for (std::size_t k = 0; k < model_.reservoirs.size(); ++k) {
    const WallReservoir& w = model_.reservoirs[k];
    const std::size_t base = static_cast<std::size_t>(w.species) * n_;
    if (w.voxels.empty()) {
      for (std::size_t i = 0; i < n_; ++i) {
        if (graph_.is_wall[i] && !explicit_set[base + i])
          reservoir_conc_[base + i] = w.concentration;
      }
      continue;
    }
    for (std::uint32_t v : w.voxels) {
      if (v >= n_ || !graph_.is_wall[v]) {
        throw InvalidArgument("reservoirs[" + std::to_string(k) + "].voxels contains " +
                                  std::to_string(v) + ", which is not a wall particle",
                              {{"field", "reservoirs.voxels"}, {"value", std::to_string(v)}});
      }
      if (explicit_set[base + v]) {
        throw InvalidArgument("reservoirs[" + std::to_string(k) + "].voxels: wall particle " +
                                  std::to_string(v) + " already has a reservoir for species " +
                                  std::to_string(w.species),
                              {{"field", "reservoirs.voxels"}, {"value", std::to_string(v)}});
      }
      explicit_set[base + v] = 1;
      reservoir_conc_[base + v] = w.concentration;
    }
  }
}

std::int64_t RdmeState::reservoir_count(int s, std::uint32_t i) const {
  return static_cast<std::int64_t>(
      std::llround(reservoir_conc_[static_cast<std::size_t>(s) * n_ + i] * graph_.volume[i]));
}

bool RdmeState::apply_reservoirs() {
  bool changed = false;
  if (!has_walls_) return false;
  for (std::size_t s = 0; s < reservoir_.size(); ++s) {
    if (!reservoir_[s]) continue;
    for (std::size_t i = 0; i < n_; ++i) {
      if (!graph_.is_wall[i]) continue;
      const std::int64_t x = reservoir_count(static_cast<int>(s), static_cast<std::uint32_t>(i));
      if (counts_[s * n_ + i] != x) {
        counts_[s * n_ + i] = x;
        changed = true;
      }
    }
  }
  return changed;
}

void RdmeState::set_counts(int species, std::span<const std::int64_t> counts) {
  if (!has_graph()) {
    throw FailedPrecondition("set_counts: call update_graph() first (the voxel count is unknown)");
  }
  if (species < 0 || species >= species_count()) {
    throw InvalidArgument("set_counts: species = " + std::to_string(species) + " (allowed: 0.." +
                          std::to_string(species_count() - 1) + ")");
  }
  if (counts.size() != n_) {
    throw InvalidArgument("set_counts: counts has " + std::to_string(counts.size()) +
                          " entries, expected " + std::to_string(n_) + " (one per particle)");
  }
  for (std::size_t i = 0; i < n_; ++i) {
    if (counts[i] < 0) {
      throw InvalidArgument("set_counts: counts[" + std::to_string(i) +
                            "] = " + std::to_string(counts[i]) + " for species '" +
                            model_.species[species].name + "' (allowed: >= 0)");
    }
  }
  std::copy(counts.begin(), counts.end(), counts_.begin() + species * n_);
  apply_reservoirs();
}

std::span<const std::int64_t> RdmeState::counts(int species) const {
  if (species < 0 || species >= species_count()) {
    throw InvalidArgument("counts: species = " + std::to_string(species) + " (allowed: 0.." +
                          std::to_string(species_count() - 1) + ")");
  }
  return {counts_.data() + species * n_, n_};
}

void RdmeState::restore_counts(std::vector<std::int64_t> counts) {
  if (counts.size() != counts_.size()) {
    throw InvalidArgument("restore: counts has " + std::to_string(counts.size()) +
                          " entries, expected " + std::to_string(counts_.size()));
  }
  counts_ = std::move(counts);
}

void RdmeState::apply_reaction(std::size_t r, std::uint32_t i) {
  for (const auto& [s, delta] : table_.reaction(r).change) {
    if (fixed(s, i)) continue;
    std::int64_t& x = counts_[s * n_ + i];
    x += delta;
    assert(x >= 0);
  }
}

std::uint32_t RdmeState::apply_jump(int s, std::uint32_t i, std::uint32_t j) {
  if (!fixed(s, i)) {
    assert(counts_[s * n_ + i] > 0);
    --counts_[s * n_ + i];
  }
  if (fixed(s, j)) return kNoVoxel;  // absorbed by the reservoir
  ++counts_[s * n_ + j];
  return j;
}

std::uint32_t RdmeState::fire(std::uint32_t i, double u) {
  // Last channel with a positive propensity: the fallback when round-off puts
  // u at or beyond the recomputed sum.
  int last_kind = -1;  // 0 reaction, 1 diffusion
  std::size_t last_index = 0;
  double last_p = 0;
  if (voxels_[i].active) {
    for (std::size_t r = 0; r < table_.reaction_count(); ++r) {
      const double p = table_.propensity(r, i, counts_.data(), n_);
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
    const std::uint32_t end = edge_end(s, i);
    return apply_jump(s, i, graph_.edges[end - 1].target);
  }
  (void)last_p;
  throw Error(StatusCode::kInternal,
              "RdmeState::fire: voxel " + std::to_string(i) + " has zero total rate");
}

}  // namespace sadr::ssa
