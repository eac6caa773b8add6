// SPDX-License-Identifier: MIT
#include "sadr/ssa/reaction_table.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>

#include "sadr/common/status.hpp"

namespace sadr::ssa {

namespace {

CompiledReaction compile(const Reaction& rx) {
  CompiledReaction c;
  const bool has_law = rx.def.law.has_value();
  std::map<int, int> net;
  for (const auto& [s, nu] : rx.reactants) {
    if (!has_law) {  // the mass-action form (at most 2 reactants, Model::validate)
      c.species[c.n_reactants] = s;
      c.nu[c.n_reactants] = nu;
      ++c.n_reactants;
    }
    c.order += nu;
    net[s] -= nu;
  }
  for (const auto& [s, nu] : rx.products) net[s] += nu;
  for (const auto& [s, delta] : net) {
    if (delta != 0) c.change.emplace_back(s, delta);
  }
  return c;
}

}  // namespace

ReactionTable ReactionTable::build(const Model& model, const DiffusionGraph& graph) {
  ReactionTable t;
  const std::size_t n = graph.size();
  t.species_ = model.law_names();
  t.ns_ = static_cast<int>(model.species.size());
  std::size_t widest = 0;
  for (const Reaction& rx : model.reactions) {
    t.reactions_.push_back(compile(rx));
    t.names_.push_back(rx.def.name);
    const std::vector<double>& areas = rx.def.boundary_areas;
    if (rx.def.law) {
      t.reactions_.back().law = static_cast<int>(t.laws_.size());
      rate_law::RateLaw law(*rx.def.law, t.species_);
      const auto& sp = law.species();
      const bool external =
          law.uses_time() || std::any_of(sp.begin(), sp.end(), [&](int s) { return s >= t.ns_; });
      t.has_external_ = t.has_external_ || external;
      t.laws_.push_back(
          {std::move(law), rx.reactants, t.reactions_.size() - 1, external, !areas.empty()});
      if (!areas.empty()) t.volume_ = graph.volume;
      widest = std::max(widest, t.laws_.back().law.species().size());
    }
  }
  t.scratch_.assign(widest, 0.0);
  for (const NeumannSource& src : model.neumann) {
    CompiledReaction c;
    c.change.emplace_back(src.species, 1);
    t.reactions_.push_back(c);
  }
  const std::size_t nr = t.reactions_.size();
  t.c_.assign(n * nr, 0.0);
  t.active_.assign(n, 0);
  std::vector<std::uint8_t> in_region(n);
  for (std::size_t r = 0; r < model.reactions.size(); ++r) {
    const Reaction& rx = model.reactions[r];
    const model::Reaction& def = rx.def;
    if (!def.law && def.rate == 0) continue;
    std::fill(in_region.begin(), in_region.end(), rx.voxels.empty() ? 1 : 0);
    for (std::uint32_t v : rx.voxels) in_region[v] = 1;
    if (!def.boundary_areas.empty()) {  // a boundary flux: c = A_i in its fluid voxels (a = A_i j)
      for (std::size_t k = 0; k < rx.voxels.size(); ++k) {
        const std::uint32_t i = rx.voxels[k];
        if (graph.kind[i] == ParticleKind::kFluid) t.c_[i * nr + r] = def.boundary_areas[k];
      }
      continue;
    }
    for (std::size_t i = 0; i < n; ++i) {
      const bool kind_ok = def.kinds.empty() ? graph.kind[i] == ParticleKind::kFluid
                                             : std::find(def.kinds.begin(), def.kinds.end(),
                                                         graph.kind[i]) != def.kinds.end();
      if (!kind_ok || !in_region[i]) continue;
      t.c_[i * nr + r] =
          def.law ? graph.volume[i]
                  : mass_action::voxel_constant(def.rate, t.reactions_[r].order, graph.volume[i]);
    }
  }
  // Neumann: the first layer of non-wall particles, i.e. those with a wall
  // particle closer than 1.5 l_i, l_i = V_i^(1/d) the particle spacing. Each
  // receives flux * l_i^(d-1) molecules per unit time (its share of wall area).
  const double d = graph.dimension;
  for (std::size_t k = 0; k < model.neumann.size(); ++k) {
    const std::size_t r = model.reactions.size() + k;
    if (model.neumann[k].flux == 0) continue;
    for (std::size_t i = 0; i < n; ++i) {
      if (graph.is_wall[i]) continue;
      const double l = std::pow(graph.volume[i], 1.0 / d);
      if (graph.wall_distance[i] < 1.5 * l) {
        t.c_[i * nr + r] = model.neumann[k].flux * std::pow(l, d - 1.0);
      }
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t r = 0; r < nr; ++r) t.active_[i] |= t.c_[i * nr + r] > 0 ? 1 : 0;
  }
  return t;
}

double ReactionTable::law_propensity(std::size_t r, std::uint32_t i, double constant,
                                     const std::int64_t* counts, std::size_t n_voxels) const {
  const LawEntry& entry = laws_[reactions_[r].law];
  // A volume law: constant = V_i, a = V_i v(C). A boundary flux: constant = A_i, a = A_i j(C).
  const double volume = entry.areal ? volume_[i] : constant;
  for (const auto& [s, nu] : entry.needs) {
    if (counts[s * n_voxels + i] < nu) return 0.0;  // a reactant is missing
  }
  const rate_law::RateLaw& law = entry.law;
  const std::vector<int>& sp = law.species();
  double* c = scratch_.data();
  for (std::size_t k = 0; k < sp.size(); ++k) {
    c[k] = sp[k] < ns_ ? static_cast<double>(counts[sp[k] * n_voxels + i]) / volume
                       : frozen_[(sp[k] - ns_) * n_voxels + i];
  }
  const double a = constant * law.density(c, input_time_);
  if (a >= 0 && a < std::numeric_limits<double>::infinity()) return a;
  std::string state;
  for (std::size_t k = 0; k < sp.size(); ++k) {
    state += (k ? ", " : "") + species_[sp[k]] +
             (sp[k] < ns_ ? " = " + std::to_string(counts[sp[k] * n_voxels + i])
                          : " (frozen concentration) = " + format_value(c[k]));
  }
  if (law.uses_time()) state += ", t = " + format_value(input_time_);
  throw NumericalFailure("reaction '" + names_[r] + "' (" + law.definition().text() +
                         "): propensity " + std::to_string(a) + " in voxel " + std::to_string(i) +
                         " (V = " + std::to_string(volume) + ", counts {" + state +
                         "}); allowed: a finite propensity >= 0");
}

}  // namespace sadr::ssa
