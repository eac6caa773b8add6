// SPDX-License-Identifier: MIT
#include "sadr/ssa/rdme_state.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "sadr/common/status.hpp"
#include "sadr/ssa/morris_walls.hpp"

namespace sadr::ssa {

RdmeState::RdmeState(Model model) : model_(std::move(model)) {
  model_.validate();
  const std::size_t ns = model_.species.size();
  kappa_.resize(ns);
  reservoir_.assign(ns, 0);
  for (std::size_t s = 0; s < ns; ++s) {
    kappa_[s] = model_.species[s].def.diffusivity;
    if (kappa_[s] > 0) diffusing_.push_back(static_cast<int>(s));
  }
  for (const WallReservoir& w : model_.reservoirs) reservoir_[w.species] = 1;
  free_slot_.assign(ns, -1);
  int slots = 0;
  for (const FreeWall& fw : model_.free_walls) {
    if (free_slot_[fw.species] < 0) free_slot_[fw.species] = slots++;
  }
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
  // Voxel lists that name particles: checked before anything is overwritten.
  auto check_walls = [&](const char* what, std::size_t k, const std::vector<std::uint32_t>& v) {
    if (!v.empty()) particles.validate();  // array lengths, before kind() is used
    for (std::uint32_t x : v) {
      if (x >= particles.size() || particles.kind(x) != ParticleKind::kWall) {
        throw InvalidArgument(
            std::string(what) + "[" + std::to_string(k) + "].voxels contains " + std::to_string(x) +
                ", which is not a wall particle (allowed: " + "wall particles among 0.." +
                std::to_string(static_cast<long>(particles.size()) - 1) + ")",
            {{"field", std::string(what) + ".voxels"}, {"value", std::to_string(x)}});
      }
    }
  };
  for (std::size_t k = 0; k < model_.reservoirs.size(); ++k) {
    check_walls("reservoirs", k, model_.reservoirs[k].voxels);
  }
  for (std::size_t k = 0; k < model_.free_walls.size(); ++k) {
    check_walls("free_walls", k, model_.free_walls[k].voxels);
  }
  for (std::size_t k = 0; k < model_.morris_walls.size(); ++k) {
    for (const std::uint32_t x : model_.morris_walls[k].voxels) {
      if (x >= particles.size()) {
        throw InvalidArgument("morris_walls[" + std::to_string(k) + "].voxels contains " +
                                  std::to_string(x) + " (allowed: 0.." +
                                  std::to_string(static_cast<long>(particles.size()) - 1) + ")",
                              {{"field", "morris_walls.voxels"}, {"value", std::to_string(x)}});
      }
    }
  }
  builder_.build(graph_, model_, particles);  // validates before writing
  if (!model_.morris_walls.empty() || !model_.morris_tangents.empty()) {
    apply_morris_walls(graph_, model_, particles, assign_morris_walls(model_, graph_));
  }
  // The external laws' inputs survive a rebuild (zeros, t = 0 until the first set_inputs).
  const double input_time = table_.input_time();
  std::vector<double> frozen = table_.frozen();
  table_ = ReactionTable::build(model_, graph_);
  n_ = graph_.size();
  if (frozen.size() != model_.frozen_species.size() * n_) {
    frozen.assign(model_.frozen_species.size() * n_, 0.0);
  }
  table_.set_inputs(input_time, std::move(frozen));
  voxels_.resize(n_);
  for (std::size_t i = 0; i < n_; ++i) {
    VoxelRecord& v = voxels_[i];  // v.rate (the solver's cached rate) is kept: see
                                  // NsmSolver::rescale_queue()
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
  law_readers_.clear();
  if (table_.law_count() > 0) {
    law_readers_.resize(model_.species.size());
    for (std::size_t k = 0; k < table_.law_count(); ++k) {
      for (const int s : table_.law(table_.law_reaction(static_cast<int>(k))).species()) {
        if (s < species_count()) law_readers_[s].push_back(static_cast<int>(k));  // not frozen
      }
    }
  }
  assign_free_walls();
  assign_reservoir_concentrations();
  compute_free_sums();
  apply_reservoirs();
  refresh_all_laws();
  return true;
}

void RdmeState::set_inputs(double t, std::span<const double> frozen) {
  const std::size_t want = model_.frozen_species.size() * n_;
  if (frozen.size() != want) {
    throw InvalidArgument("frozen concentrations: " + std::to_string(frozen.size()) +
                              " values, expected " + std::to_string(want) + " (" +
                              std::to_string(model_.frozen_species.size()) + " species x " +
                              std::to_string(n_) + " voxels)",
                          {{"field", "frozen"}, {"value", std::to_string(frozen.size())}});
  }
  for (std::size_t k = 0; k < frozen.size(); ++k) {
    if (!(frozen[k] >= 0) || !std::isfinite(frozen[k])) {
      const std::string& name = model_.frozen_species[k / std::max<std::size_t>(n_, 1)];
      throw InvalidArgument("frozen concentration of '" + name + "' in voxel " +
                                std::to_string(k % n_) + " = " + format_value(frozen[k]) +
                                " (allowed: finite and >= 0)",
                            {{"field", "frozen." + name}, {"value", format_value(frozen[k])}});
    }
  }
  if (!(std::isfinite(t))) {
    throw InvalidArgument("input time = " + format_value(t) + " (allowed: finite)");
  }
  table_.set_inputs(t, std::vector<double>(frozen.begin(), frozen.end()));
  const std::size_t nl = table_.law_count();
  for (std::size_t k = 0; k < nl; ++k) {
    if (!table_.external(static_cast<int>(k))) continue;
    const std::size_t r = table_.law_reaction(static_cast<int>(k));
    for (std::size_t i = 0; i < n_; ++i) {
      law_a_[i * nl + k] = table_.propensity(r, static_cast<std::uint32_t>(i), counts_.data(), n_);
    }
  }
}

void RdmeState::refresh_all_laws() {
  const std::size_t nl = table_.law_count();
  law_a_.assign(n_ * nl, 0.0);
  for (std::size_t k = 0; k < nl; ++k) {
    const std::size_t r = table_.law_reaction(static_cast<int>(k));
    for (std::size_t i = 0; i < n_; ++i) {
      law_a_[i * nl + k] = table_.propensity(r, static_cast<std::uint32_t>(i), counts_.data(), n_);
    }
  }
}

void RdmeState::assign_free_walls() {
  int slots = 0;
  for (int slot : free_slot_) slots = std::max(slots, slot + 1);
  free_mask_.assign(static_cast<std::size_t>(slots) * n_, 0);
  for (std::size_t k = 0; k < model_.free_walls.size(); ++k) {
    const FreeWall& fw = model_.free_walls[k];
    const std::size_t base = static_cast<std::size_t>(free_slot_[fw.species]) * n_;
    if (fw.voxels.empty()) {
      for (std::size_t i = 0; i < n_; ++i) {
        if (graph_.is_wall[i] && free_mask_[base + i] == 0) free_mask_[base + i] = 1;
      }
      continue;
    }
    for (std::uint32_t v : fw.voxels) {
      if (v >= n_ || !graph_.is_wall[v]) {
        throw InvalidArgument("free_walls[" + std::to_string(k) + "].voxels contains " +
                                  std::to_string(v) + ", which is not a wall particle (allowed: " +
                                  "wall particles among 0.." + std::to_string(n_ - 1) + ")",
                              {{"field", "free_walls.voxels"}, {"value", std::to_string(v)}});
      }
      free_mask_[base + v] = 2;
    }
  }
}

void RdmeState::compute_free_sums() {
  free_sum_.assign(free_mask_.size(), 0.0);
  for (std::size_t s = 0; s < free_slot_.size(); ++s) {
    if (free_slot_[s] < 0) continue;
    const std::size_t base = static_cast<std::size_t>(free_slot_[s]) * n_;
    for (std::uint32_t i = 0; i < n_; ++i) {
      double sum = 0;  // in row order, the order fire() scans
      for (std::uint32_t k = voxels_[i].begin; k < voxels_[i].end; ++k) {
        if (uses_edge(static_cast<int>(s), i, k)) sum += graph_.edges[k].weight;
      }
      free_sum_[base + i] = sum;
    }
  }
}

void RdmeState::assign_reservoir_concentrations() {
  reservoir_conc_.assign(model_.species.size() * n_, 0.0);
  // Precedence: a reservoir listing the wall in `voxels`, else an all-walls one, else 0.
  std::vector<std::uint8_t> explicit_set(reservoir_conc_.size(), 0);
  for (std::size_t k = 0; k < model_.reservoirs.size(); ++k) {
    const WallReservoir& w = model_.reservoirs[k];
    const std::size_t base = static_cast<std::size_t>(w.species) * n_;
    const int slot = free_slot_[w.species];
    const std::uint8_t* free = slot >= 0 ? free_mask_.data() + slot * n_ : nullptr;
    if (w.voxels.empty()) {
      for (std::size_t i = 0; i < n_; ++i) {
        if (graph_.is_wall[i] && !explicit_set[base + i] && !(free && free[i])) {
          reservoir_conc_[base + i] = w.concentration;
        }
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
      if (free && free[v] == 2) {
        throw InvalidArgument("reservoirs[" + std::to_string(k) + "].voxels: wall particle " +
                                  std::to_string(v) + " is also listed free for species " +
                                  std::to_string(w.species) + " (allowed: one of them)",
                              {{"field", "reservoirs.voxels"}, {"value", std::to_string(v)}});
      }
      if (free) free_mask_[slot * n_ + v] = 0;  // an explicit reservoir beats all-walls free
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
      if (!fixed(static_cast<int>(s), static_cast<std::uint32_t>(i))) continue;
      const std::int64_t x = reservoir_count(static_cast<int>(s), static_cast<std::uint32_t>(i));
      if (counts_[s * n_ + i] != x) {
        counts_[s * n_ + i] = x;
        changed = true;
      }
    }
  }
  if (changed) refresh_all_laws();
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
                            model_.species[species].def.name + "' (allowed: >= 0)");
    }
  }
  std::copy(counts.begin(), counts.end(), counts_.begin() + species * n_);
  apply_reservoirs();
  refresh_all_laws();
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
  counts_.assign(counts.begin(), counts.end());
  refresh_all_laws();
}

void RdmeState::apply_reaction(std::size_t r, std::uint32_t i) {
  for (const auto& [s, delta] : table_.reaction(r).change) {
    if (fixed(s, i)) continue;
    std::int64_t& x = counts_[s * n_ + i];
    x += delta;
    assert(x >= 0);
    refresh_laws(s, i);
  }
}

std::uint32_t RdmeState::apply_jump(int s, std::uint32_t i, std::uint32_t j) {
  if (!fixed(s, i)) {
    assert(counts_[s * n_ + i] > 0);
    --counts_[s * n_ + i];
    refresh_laws(s, i);
  }
  if (fixed(s, j)) return kNoVoxel;  // absorbed by the reservoir
  ++counts_[s * n_ + j];
  refresh_laws(s, j);
  return j;
}

}  // namespace sadr::ssa
