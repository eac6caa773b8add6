// SPDX-License-Identifier: MIT
#include "sadr/ssa/reaction_table.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace sadr::ssa {

namespace {

CompiledReaction compile(const Reaction& rx) {
  CompiledReaction c;
  std::map<int, int> net;
  for (const auto& [s, nu] : rx.reactants) {
    c.species[c.n_reactants] = s;
    c.nu[c.n_reactants] = nu;
    ++c.n_reactants;
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
  for (const Reaction& rx : model.reactions) t.reactions_.push_back(compile(rx));
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
    if (rx.rate == 0) continue;
    std::fill(in_region.begin(), in_region.end(), rx.voxels.empty() ? 1 : 0);
    for (std::uint32_t v : rx.voxels) in_region[v] = 1;
    for (std::size_t i = 0; i < n; ++i) {
      const bool kind_ok = rx.kinds.empty() ? graph.kind[i] == ParticleKind::kFluid
                                            : std::find(rx.kinds.begin(), rx.kinds.end(),
                                                        graph.kind[i]) != rx.kinds.end();
      if (!kind_ok || !in_region[i]) continue;
      t.c_[i * nr + r] =
          mass_action::voxel_constant(rx.rate, t.reactions_[r].order, graph.volume[i]);
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

}  // namespace sadr::ssa
