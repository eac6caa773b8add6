// SPDX-License-Identifier: MIT
/// \file sdpd_limits.cpp
/// SdpdBackend: the stability limits of a sub-step (docs/fluid-core.md) and the health check.
#include <algorithm>
#include <cmath>
#include <limits>

#include "sadr/fluid/parallel.hpp"
#include "sdpd_backend.hpp"

namespace sadr::fluid {

StabilityLimits SdpdBackend::limits(const Y& y, const Rates& r) const {
  const std::size_t n = mass_.size();
  double vmax2 = 0, rho_min = std::numeric_limits<double>::infinity(), amax2 = 0;
  const auto ni = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static) if (ni > kMinParallelLight) reduction(max             \
                                                                                : vmax2, amax2) \
    reduction(min                                                                               \
              : rho_min)
  for (std::int64_t ii = 0; ii < ni; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    if (wall_[i]) continue;
    const double* v = &y.v[3 * i];
    vmax2 = std::max(vmax2, v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    rho_min = std::min(rho_min, y.rho[i]);
    double a[3];
    body_acceleration(i, y.c, a);
    amax2 = std::max(amax2, a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  }
  return limits_from(vmax2, rho_min, amax2, r.max_visc_sum, r.max_k_sum, y);
}

StabilityLimits SdpdBackend::limits_from(double vmax2, double rho_min, double amax2,
                                         double max_visc_sum, double max_k_sum, const Y& y) const {
  StabilityLimits lim;
  const double h = kernel_.support();
  // The coefficients (docs/method.md) are Morris' for the smoothing length h_M = h/2
  // (support = 2 h_M).
  const double hm = 0.5 * h;
  lim.acoustic = 0.25 * hm / (model_.sound_speed + std::sqrt(vmax2));
  if (model_.shear_viscosity > 0 && std::isfinite(rho_min)) {
    lim.viscous = 0.125 * rho_min * hm * hm / model_.shear_viscosity;
    if (max_visc_sum > 0)
      lim.viscous = std::min(lim.viscous, 1.0 / (model_.shear_viscosity * max_visc_sum));
  }
  if (amax2 > 0) lim.body_force = 0.25 * std::sqrt(hm / std::sqrt(amax2));
  const double kmax = species_.max_diffusivity();
  if (kmax > 0) {
    lim.diffusion = 0.125 * hm * hm / kmax;
    if (max_k_sum > 0) lim.diffusion = std::min(lim.diffusion, 1.0 / (2.0 * kmax * max_k_sum));
  }
  if (species_.has_reactions()) {
    ParticleState shape;
    shape.densities = y.rho;
    const double j = species_.reaction_rate_scale(y.c, shape);
    if (j > 0) lim.reaction = 1.0 / j;
  }
  return lim;
}

void SdpdBackend::throw_too_many_substeps(std::uint64_t step_index, const std::string& limit_name,
                                          double limit) {
  throw NumericalFailure("sdpd: more than " + std::to_string(kMaxSubsteps) +
                             " sub-steps needed in one coupling step (limit '" + limit_name +
                             "' = " + format_value(limit) +
                             "); shorten time.coupling_step in the scene",
                         {{"step", std::to_string(step_index)}, {"limit", limit_name}});
}

StabilityLimits SdpdBackend::current_limits() {
  require_initialized("current_limits");
  // On copies: evaluate() writes the summation densities into its Y, and r0_ is the step's.
  Y y = y_;
  Rates r;
  species_.set_time(time_);  // the laws of t (as a sub-step starting now)
  evaluate(y, 0, r, false);
  return limits(y, r);
}

void SdpdBackend::check_health(std::uint64_t step_index, std::uint32_t substep) const {
  HealthView h{y_.x, y_.v, y_.c, model_.species, ids_, pbox_};
  h.rho = &y_.rho;
  h.rho0 = model_.reference_density;
  h.band = model_.density_band;
  fluid::check_health(name(), h, step_index, substep);
}

}  // namespace sadr::fluid
