// SPDX-License-Identifier: MIT
#include "sadr/fluid/species_transport.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "sadr/common/mass_action.hpp"
#include "sadr/common/status.hpp"
#include "sadr/fluid/parallel.hpp"

namespace sadr::fluid {

void SpeciesTransport::setup(const FluidModel& model, const ParticleState& state) {
  const std::size_t n = state.size();
  const int ns = static_cast<int>(model.species.size());
  const int nr = static_cast<int>(model.wall_regions.size());
  transported_.clear();
  two_kappa_.assign(ns, 0.0);
  max_kappa_ = 0;
  normal_.clear();
  for (const auto& w : model.wall_regions) normal_.push_back(w.inward_normal);
  region_ = model.assign_wall_regions(state);
  reacts_.assign(n, 0);
  active_wall_.assign(n, 0);
  roles_.assign(ns, {});
  neumann_grad_.assign(ns, std::vector<double>(nr + 1, 0.0));
  dirichlet_.assign(ns, std::vector<double>(nr + 1, 0.0));
  for (int s = 0; s < ns; ++s) {
    const auto& sp = model.species[s];
    const double kappa = sp.def.diffusivity;
    if (sp.deterministic()) transported_.push_back(s);
    two_kappa_[s] = 2.0 * kappa;
    if (sp.deterministic()) max_kappa_ = std::max(max_kappa_, kappa);
    auto cond = [&](int reg) -> const WallCondition& {
      return (reg < 0 || sp.wall_conditions.empty()) ? sp.default_wall : sp.wall_conditions[reg];
    };
    for (int reg = -1; reg < nr; ++reg) {
      const auto& wc = cond(reg);
      dirichlet_[s][reg + 1] = wc.value;
      neumann_grad_[s][reg + 1] = kappa > 0 ? wc.value / kappa : 0.0;
    }
    roles_[s].assign(n, Role::kFree);
    for (std::size_t i = 0; i < n; ++i) {
      if (state.kind(i) != ParticleKind::kWall) continue;
      switch (cond(region_[i]).type) {
        case WallCondition::Type::kNoFlux:
          roles_[s][i] = Role::kNoFlux;
          break;
        case WallCondition::Type::kDirichlet:
          roles_[s][i] = Role::kDirichlet;
          break;
        case WallCondition::Type::kNeumann:
          roles_[s][i] = Role::kNeumann;
          break;
        case WallCondition::Type::kFree:
          roles_[s][i] = Role::kFree;
          if (sp.deterministic()) active_wall_[i] = 1;
          break;
      }
    }
  }
  reactions_.clear();
  std::vector<rate_law::RateLaw> laws;
  std::vector<std::string> names;
  for (const auto& sp : model.species) names.push_back(sp.def.name);
  std::size_t widest = 0;
  for (std::size_t r = 0; r < model.reactions.size(); ++r) {
    const auto& re = model.reactions[r];
    const model::Reaction& def = re.def;
    CompiledReaction cr;
    cr.rate = def.rate;
    if (def.law) {
      cr.law = static_cast<int>(laws.size());
      laws.emplace_back(*def.law, names);
      widest = std::max(widest, laws.back().species().size());
    }
    // Sites: kinds (default fluid only) intersected with the optional particle list.
    cr.kind_ok = {1, 0, 0, 0};
    if (!def.kinds.empty()) {
      cr.kind_ok[0] = 0;
      for (const ParticleKind k : def.kinds) {
        const auto ki = static_cast<std::size_t>(k);
        if (ki < 4) cr.kind_ok[ki] = 1;
      }
    }
    cr.fires.assign(n, 0);
    auto site = [&](std::size_t i) {
      const auto ki = static_cast<std::size_t>(state.kind(i));
      if (ki < 4 && cr.kind_ok[ki]) cr.fires[i] = 1;
    };
    if (re.particles.empty()) {
      for (std::size_t i = 0; i < n; ++i) site(i);
    } else {
      cr.listed.assign(n, 0);
      for (std::size_t k = 0; k < re.particles.size(); ++k) {
        const std::uint32_t i = re.particles[k];
        if (i >= n) {
          throw InvalidArgument("reactions[" + std::to_string(r) + "].particles[" +
                                std::to_string(k) + "] = " + std::to_string(i) +
                                " (must index a particle, [0, " + std::to_string(n) + "))");
        }
        cr.listed[i] = 1;
        site(i);
      }
    }
    if (!def.boundary_areas.empty()) {  // a boundary flux: j A_i / V_i (sizes: validate())
      cr.scale.assign(n, 0.0);
      for (std::size_t k = 0; k < re.particles.size(); ++k) {
        const std::uint32_t i = re.particles[k];
        cr.scale[i] = def.boundary_areas[k] / state.volume(i);
      }
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (!cr.fires[i]) continue;
      reacts_[i] = 1;
      if (state.kind(i) == ParticleKind::kWall) active_wall_[i] = 1;
    }
    std::map<int, int> net;
    for (const auto& [s, nu] : re.reactants) {
      cr.reactants.push_back({s, nu, mass_action::inverse_factorial(nu)});
      net[s] -= nu;
    }
    for (const auto& [s, nu] : re.products) net[s] += nu;
    for (const auto& [s, d] : net) {
      if (d != 0) cr.delta.emplace_back(s, d);
    }
    reactions_.push_back(std::move(cr));
  }
  const auto threads = static_cast<std::size_t>(std::max(1, max_threads()));
  laws_.assign(threads, laws);
  scratch_.assign(threads, std::vector<double>(widest, 0.0));
}

void SpeciesTransport::apply_dirichlet(std::vector<std::vector<double>>& c) const {
  for (std::size_t s = 0; s < roles_.size(); ++s) {
    for (std::size_t i = 0; i < roles_[s].size(); ++i) {
      if (roles_[s][i] == Role::kDirichlet) c[s][i] = dirichlet_[s][region_[i] + 1];
    }
  }
}

double SpeciesTransport::velocity(const CompiledReaction& r, std::size_t i,
                                  const std::vector<std::vector<double>>& c) const {
  if (r.law >= 0) {
    const auto thread = static_cast<std::size_t>(thread_index());
    if (thread >= laws_.size()) {
      throw Error(StatusCode::kInternal, "SpeciesTransport: thread " + std::to_string(thread) +
                                             " beyond the " + std::to_string(laws_.size()) +
                                             " set up");
    }
    const rate_law::RateLaw& law = laws_[thread][r.law];
    double* x = scratch_[thread].data();
    const std::vector<int>& sp = law.species();
    for (std::size_t k = 0; k < sp.size(); ++k) x[k] = c[sp[k]][i];
    return law.density(x, time_);
  }
  double v = r.rate;
  for (const auto& t : r.reactants) {
    v *= mass_action::concentration_term(c[t.species][i], t.nu, t.inv_factorial);
  }
  return v;
}

double SpeciesTransport::law_rate_scale(const CompiledReaction& r, std::size_t i,
                                        const std::vector<std::vector<double>>& c) const {
  // sum_s |dv/dC_s| times the total |stoichiometric change|: a Gershgorin bound on
  // this reaction's Jacobian (one-sided differences; serial, thread 0's copy).
  const rate_law::RateLaw& law = laws_[0][r.law];
  double* x = scratch_[0].data();
  const std::vector<int>& sp = law.species();
  for (std::size_t k = 0; k < sp.size(); ++k) x[k] = c[sp[k]][i];
  double grad = 0;
  for (std::size_t k = 0; k < sp.size(); ++k) grad += std::fabs(law.derivative(x, time_, k));
  double change = 0;
  for (const auto& [s, d] : r.delta) change += std::abs(d);
  return grad * change;
}

void SpeciesTransport::update_sites(std::span<const ParticleKind> kinds) {
  const std::size_t n = reacts_.size();
  if (kinds.size() != n) {
    throw InvalidArgument("update_sites: " + std::to_string(kinds.size()) + " kinds for " +
                          std::to_string(n) + " particles");
  }
  std::fill(reacts_.begin(), reacts_.end(), 0);
  for (CompiledReaction& cr : reactions_) {
    for (std::size_t i = 0; i < n; ++i) {
      const auto ki = static_cast<std::size_t>(kinds[i]);
      cr.fires[i] = (cr.listed.empty() || cr.listed[i]) && ki < 4 && cr.kind_ok[ki] ? 1 : 0;
      reacts_[i] |= cr.fires[i];
    }
  }
}

void SpeciesTransport::add_reactions(std::size_t i, const std::vector<std::vector<double>>& c,
                                     std::vector<std::vector<double>>& dc) const {
  if (!reacts_[i]) return;
  for (const auto& r : reactions_) {
    if (!r.fires[i]) continue;
    const double v = r.scale.empty() ? velocity(r, i, c) : velocity(r, i, c) * r.scale[i];
    for (const auto& [s, d] : r.delta) {
      if (roles_[s][i] != Role::kDirichlet) dc[s][i] += d * v;
    }
  }
}

double SpeciesTransport::reaction_rate_scale(const std::vector<std::vector<double>>& c,
                                             const ParticleState& state) const {
  double worst = 0;
  (void)state;
  for (std::size_t i = 0; i < reacts_.size(); ++i) {
    if (!reacts_[i]) continue;
    double sum = 0;
    for (const auto& r : reactions_) {
      if (!r.fires[i]) continue;
      if (r.law >= 0) {
        sum += law_rate_scale(r, i, c) * (r.scale.empty() ? 1.0 : r.scale[i]);
        continue;
      }
      for (const auto& t : r.reactants) {
        // dv/dC_s = rate * nu C_s^(nu-1)/nu! * prod_{other reactants}
        double d = r.rate * t.nu * t.inv_factorial;
        for (int k = 1; k < t.nu; ++k) d *= c[t.species][i];
        for (const auto& o : r.reactants) {
          if (&o == &t) continue;
          double p = 1;
          for (int k = 0; k < o.nu; ++k) p *= c[o.species][i];
          d *= p * o.inv_factorial;
        }
        sum += t.nu * std::fabs(d);
      }
    }
    worst = std::max(worst, sum);
  }
  return worst;
}

}  // namespace sadr::fluid
