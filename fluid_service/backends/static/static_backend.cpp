// SPDX-License-Identifier: MIT
#include "static_backend.hpp"

#include <algorithm>
#include <memory>
#include <string>

#include "sadr/common/status.hpp"
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
  species_.transport().apply_dirichlet(c_);
  species_.reset_scratch(c_);
  time_ = 0;
}

StabilityLimits StaticBackend::current_limits() const {
  require_initialized("current_limits");
  return species_.limits(c_, state_);
}

StepReport StaticBackend::step(std::uint64_t step_index, double time_step) {
  StepReport rep;
  rep.stable_dt = StabilityLimits::kNone;
  rep.limiting_criterion = "none";
  std::uint32_t sub = 0;
  if (!species_.active()) {
    time_ += time_step;  // nothing evolves: zero cost
  } else {
    sub = species_.advance(name(), state_, c_, step_index, time_step, time_, rep);
  }
  rep.time = time_;
  rep.substeps = sub;
  rep.particles_moved = false;
  rep.max_speed = 0;
  rep.set_density_band(state_.densities);
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

void register_static_backend(BackendRegistry& registry) {
  registry.add("static", [] { return std::make_unique<StaticBackend>(); });
}

}  // namespace sadr::fluid
