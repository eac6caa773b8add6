// SPDX-License-Identifier: MIT
#include "sadr/fluid/species_operator.hpp"

#include <algorithm>
#include <cmath>

#include "sadr/fluid/backend_base.hpp"
#include "sadr/fluid/kernel.hpp"
#include "sadr/fluid/pair_terms.hpp"
#include "sadr/fluid/parallel.hpp"
#include "sadr/fluid/periodic_box.hpp"

namespace sadr::fluid {

void SpeciesOperator::setup(const FluidModel& model, const ParticleState& state) {
  model_ = model;
  species_.setup(model, state);
  build(state);
}

void SpeciesOperator::build(const ParticleState& state) {
  const std::size_t n = state.size();
  nlist_ = {};
  k_.clear();
  xij_.clear();
  max_k_sum_ = 0;
  if (species_.transported().empty()) return;
  const FluidModel& model = model_;
  const Kernel kernel(parse_kernel(model.kernel), model.box.dimension, model.smoothing_length);
  CellListBuilder(model.box, model.smoothing_length).build(state.positions, nlist_);
  const PeriodicBox pbox(model.box);
  const DiffusionTerm diffusion{model.diffusion_eps * model.smoothing_length *
                                model.smoothing_length};
  k_.resize(nlist_.indices.size());
  xij_.resize(3 * nlist_.indices.size());
  for (std::size_t i = 0; i < n; ++i) {
    double k_sum = 0;
    for (std::uint32_t e = nlist_.offsets[i]; e < nlist_.offsets[i + 1]; ++e) {
      const std::uint32_t j = nlist_.indices[e];
      double d[3] = {state.positions[3 * i] - state.positions[3 * j],
                     state.positions[3 * i + 1] - state.positions[3 * j + 1],
                     state.positions[3 * i + 2] - state.positions[3 * j + 2]};
      pbox.minimum_image(d);
      PairGeometry<3> g{};
      g.x = {d[0], d[1], d[2]};
      g.r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
      g.r = std::sqrt(g.r2);
      g.f = kernel.f(g.r);
      g.inv_r2 = 1.0 / g.r2;
      k_[e] = diffusion.coefficient(g, state.volume(j));
      std::copy(d, d + 3, &xij_[3 * e]);
      if (state.kind(i) != ParticleKind::kWall || species_.active_wall(i)) k_sum += k_[e];
    }
    max_k_sum_ = std::max(max_k_sum_, k_sum);
  }
}

void SpeciesOperator::rates(const ParticleState& state, const Fields& c, Fields& dc) const {
  const std::size_t n = state.size();
  for (auto& d : dc) std::fill(d.begin(), d.end(), 0.0);
  const auto ni = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static) if (ni > kMinParallel)
  for (std::int64_t ii = 0; ii < ni; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    if (state.kind(i) == ParticleKind::kWall) {
      if (!species_.active_wall(i)) continue;  // WallCondition::kFree walls / wall reactions
      for (std::uint32_t e = nlist_.offsets[i]; e < nlist_.offsets[i + 1]; ++e) {
        species_.add_pair_wall(i, nlist_.indices[e], k_[e], &xij_[3 * e], c, dc);
      }
      species_.add_reactions(i, c, dc);
      continue;
    }
    for (std::uint32_t e = nlist_.offsets[i]; e < nlist_.offsets[i + 1]; ++e) {
      species_.add_pair(i, nlist_.indices[e], k_[e], &xij_[3 * e], c, dc);
    }
    species_.add_reactions(i, c, dc);
  }
}

StabilityLimits SpeciesOperator::limits(const Fields& c, const ParticleState& state) const {
  StabilityLimits lim;
  const double h = model_.smoothing_length;
  const double kmax = species_.max_diffusivity();
  if (kmax > 0) {
    lim.diffusion = 0.125 * 0.25 * h * h / kmax;  // Morris 0.125 h_M^2/kappa, h_M = h/2
    if (max_k_sum_ > 0) lim.diffusion = std::min(lim.diffusion, 1.0 / (2.0 * kmax * max_k_sum_));
  }
  if (species_.has_reactions()) {
    const double j = species_.reaction_rate_scale(c, state);
    if (j > 0) lim.reaction = 1.0 / j;
  }
  return lim;
}

std::uint32_t SpeciesOperator::advance(std::string_view backend, const ParticleState& state,
                                       Fields& c, std::uint64_t step_index, double time_step,
                                       double& time, StepReport& rep) {
  const std::size_t n = state.size();
  if (ctmp_.size() != c.size() || (!c.empty() && ctmp_[0].size() != n)) reset_scratch(c);
  // Species held here (stochastic ones a hybrid law reads, X / V from the back-transfer)
  // are constant over the advance: the predictor stage reads them too.
  for (std::size_t s = 0; s < c.size(); ++s) {
    if (!model_.species[s].deterministic()) ctmp_[s] = c[s];
  }
  std::uint32_t sub = 0;
  double remaining = time_step;
  while (remaining > 0) {
    species_.set_time(time);  // Heun: the laws of t at both ends of the sub-step
    const double dt = next_substep(limits(c, state), model_.max_time_step, model_.force_time_step,
                                   remaining, rep.stable_dt, rep.limiting_criterion)
                          .dt;
    rates(state, c, dc0_);
    for (const int s : species_.transported()) {
      for (std::size_t i = 0; i < n; ++i) ctmp_[s][i] = c[s][i] + dt * dc0_[s][i];
    }
    species_.set_time(time + dt);
    rates(state, ctmp_, dc1_);
    for (const int s : species_.transported()) {
      for (std::size_t i = 0; i < n; ++i) {
        c[s][i] += 0.5 * dt * (dc0_[s][i] + dc1_[s][i]);
        if (!std::isfinite(c[s][i])) {
          throw_numerical_failure({backend, step_index, sub, state.ids[i],
                                   "concentration[" + model_.species[s].def.name + "]", c[s][i],
                                   "non-finite"});
        }
      }
    }
    remaining -= dt;
    if (remaining < 1e-12 * time_step) remaining = 0;
    time += dt;
    ++sub;
  }
  return sub;
}

}  // namespace sadr::fluid
