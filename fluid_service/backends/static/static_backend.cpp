// SPDX-License-Identifier: MIT
#include "static_backend.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "sadr/common/status.hpp"
#include "sadr/fluid/kernel.hpp"
#include "sadr/fluid/pair_terms.hpp"
#include "sadr/fluid/parallel.hpp"
#include "sadr/fluid/periodic_box.hpp"
#include "sadr/fluid/state_blob.hpp"

namespace sadr::fluid {

void StaticBackend::setup(const FluidModel& model, const ParticleState& initial,
                          const std::vector<std::vector<double>>& concentrations) {
  if (!model.backend_parameters.empty()) {
    throw InvalidArgument("static: unknown parameter '" + model.backend_parameters.begin()->first +
                          "' (this backend takes none beyond density_diffusion, diffusion_eps, "
                          "density_band, neighbor_skin)");
  }
  const std::size_t n = initial.size();
  model_ = model;
  state_ = initial;
  if (state_.velocities.empty()) state_.velocities.assign(3 * n, 0.0);
  std::fill(state_.velocities.begin(), state_.velocities.end(), 0.0);
  if (state_.kinds.empty()) state_.kinds.assign(n, ParticleKind::kFluid);
  if (state_.ids.empty()) {
    state_.ids.resize(n);
    for (std::size_t i = 0; i < n; ++i) state_.ids[i] = i;
  }
  c_.assign(model.species.size(), std::vector<double>(n, 0.0));
  for (std::size_t s = 0; s < concentrations.size(); ++s) c_[s] = concentrations[s];
  species_.setup(model_, state_);
  species_.apply_dirichlet(c_);
  nlist_ = {};
  k_.clear();
  xij_.clear();
  max_k_sum_ = 0;
  if (!species_.transported().empty()) {
    const Kernel kernel(parse_kernel(model.kernel), model.box.dimension, model.smoothing_length);
    CellListBuilder(model.box, model.smoothing_length).build(state_.positions, nlist_);
    const PeriodicBox pbox(model.box);
    const DiffusionTerm diffusion{model.diffusion_eps * model.smoothing_length *
                                  model.smoothing_length};
    k_.resize(nlist_.indices.size());
    xij_.resize(3 * nlist_.indices.size());
    for (std::size_t i = 0; i < n; ++i) {
      double k_sum = 0;
      for (std::uint32_t e = nlist_.offsets[i]; e < nlist_.offsets[i + 1]; ++e) {
        const std::uint32_t j = nlist_.indices[e];
        double d[3] = {state_.positions[3 * i] - state_.positions[3 * j],
                       state_.positions[3 * i + 1] - state_.positions[3 * j + 1],
                       state_.positions[3 * i + 2] - state_.positions[3 * j + 2]};
        pbox.minimum_image(d);
        PairGeometry<3> g{};
        g.x = {d[0], d[1], d[2]};
        g.r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        g.r = std::sqrt(g.r2);
        g.f = kernel.f(g.r);
        g.inv_r2 = 1.0 / g.r2;
        k_[e] = diffusion.coefficient(g, state_.volume(j));
        std::copy(d, d + 3, &xij_[3 * e]);
        if (state_.kind(i) != ParticleKind::kWall || species_.active_wall(i)) k_sum += k_[e];
      }
      max_k_sum_ = std::max(max_k_sum_, k_sum);
    }
  }
  ctmp_ = c_;
  dc0_ = c_;
  dc1_ = c_;
  time_ = 0;
}

void StaticBackend::rates(const std::vector<std::vector<double>>& c,
                          std::vector<std::vector<double>>& dc) const {
  const std::size_t n = state_.size();
  for (auto& d : dc) std::fill(d.begin(), d.end(), 0.0);
  const auto ni = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static) if (ni > kMinParallel)
  for (std::int64_t ii = 0; ii < ni; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    if (state_.kind(i) == ParticleKind::kWall) {
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

StabilityLimits StaticBackend::current_limits() const {
  require_initialized("current_limits");
  StabilityLimits lim;
  const double h = model_.smoothing_length;
  const double kmax = species_.max_diffusivity();
  if (kmax > 0) {
    lim.diffusion = 0.125 * 0.25 * h * h / kmax;  // Morris 0.125 h_M^2/kappa, h_M = h/2
    if (max_k_sum_ > 0) lim.diffusion = std::min(lim.diffusion, 1.0 / (2.0 * kmax * max_k_sum_));
  }
  if (species_.has_reactions()) {
    const double j = species_.reaction_rate_scale(c_, state_);
    if (j > 0) lim.reaction = 1.0 / j;
  }
  return lim;
}

StepReport StaticBackend::step(std::uint64_t step_index, double time_step) {
  StepReport rep;
  rep.stable_dt = StabilityLimits::kNone;
  rep.limiting_criterion = "none";
  const std::size_t n = state_.size();
  std::uint32_t sub = 0;
  if (species_.transported().empty()) {
    time_ += time_step;  // nothing evolves: zero cost
  } else {
    double remaining = time_step;
    while (remaining > 0) {
      const double dt = next_substep(current_limits(), model_.max_time_step, model_.force_time_step,
                                     remaining, rep.stable_dt, rep.limiting_criterion)
                            .dt;
      rates(c_, dc0_);
      for (const int s : species_.transported()) {
        for (std::size_t i = 0; i < n; ++i) ctmp_[s][i] = c_[s][i] + dt * dc0_[s][i];
      }
      rates(ctmp_, dc1_);
      for (const int s : species_.transported()) {
        for (std::size_t i = 0; i < n; ++i) {
          c_[s][i] += 0.5 * dt * (dc0_[s][i] + dc1_[s][i]);
          if (!std::isfinite(c_[s][i])) {
            throw_numerical_failure({name(), step_index, sub, state_.ids[i],
                                     "concentration[" + model_.species[s].name + "]", c_[s][i],
                                     "non-finite"});
          }
        }
      }
      remaining -= dt;
      if (remaining < 1e-12 * time_step) remaining = 0;
      time_ += dt;
      ++sub;
    }
  }
  rep.time = time_;
  rep.substeps = sub;
  rep.particles_moved = false;
  rep.max_speed = 0;
  const auto [mn, mx] = std::minmax_element(state_.densities.begin(), state_.densities.end());
  rep.min_density = *mn;
  rep.max_density = *mx;
  return rep;
}

void StaticBackend::save_state(BlobWriter& w) const {
  w.put(time_);
  w.put<std::uint64_t>(c_.size());
  for (const auto& c : c_) w.put_vector(c);
}

void StaticBackend::restore_state(BlobReader& r, std::uint32_t version) {
  if (version != 1)
    throw InvalidArgument("restore: blob version " + std::to_string(version) + " unsupported");
  const double t = r.get<double>();
  const auto ns = r.get<std::uint64_t>();
  if (ns != c_.size()) throw InvalidArgument("restore: species count differs from the model");
  std::vector<std::vector<double>> c;
  for (std::size_t s = 0; s < ns; ++s) c.push_back(r.get_vector<double>(state_.size()));
  r.expect_end();
  c_ = std::move(c);
  time_ = t;
}

}  // namespace sadr::fluid
