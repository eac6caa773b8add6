// SPDX-License-Identifier: MIT
/// \file sdpd_integrator.cpp
/// SdpdBackend::step: the explicit trapezoidal predictor-corrector (drawert2019 eq 24) on
/// Y = [x, v, rho, C], sub-stepped by the stability limits (next_substep). The thermal noise
/// increment of a sub-step is drawn once, at its start, and used by predictor and corrector.
/// Bulk fluids with the continuity density take fused_substep (sdpd_fused_step.cpp, the same
/// operations in two parallel regions); everything else general_substep.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "sadr/common/status.hpp"
#include "sadr/fluid/parallel.hpp"
#include "sdpd_backend.hpp"

namespace sadr::fluid {

StepReport SdpdBackend::step(std::uint64_t step_index, double time_step) {
  const std::size_t n = mass_.size();
  StepReport rep;
  rep.stable_dt = StabilityLimits::kNone;
  rep.limiting_criterion = "none";
  double remaining = time_step;
  std::uint32_t sub = 0;
  ytmp_.c.resize(y_.c.size());
  const bool fused = fused_ok();
  if (!bodies_.walls.empty()) take_body_forces();  // (drops what a failed step left)
  while (remaining > 0) {
    const std::uint64_t key = (step_index << 16) | sub;
    bool check = true;
    double dt = 0;
    if (!fused) {
      dt = general_substep(step_index, key, remaining, sub, rep);
    } else if (model_.box.dimension == 1) {
      dt = fused_substep<1>(step_index, key, remaining, sub, rep, check);
    } else if (model_.box.dimension == 2) {
      dt = fused_substep<2>(step_index, key, remaining, sub, rep, check);
    } else {
      dt = fused_substep<3>(step_index, key, remaining, sub, rep, check);
    }
    remaining -= dt;
    if (remaining < 1e-12 * time_step) remaining = 0;
    time_ += dt;
    ++sub;
    if (!fused && open_.enabled()) apply_open_boundary(dt);
    if (check) check_health(step_index, sub);
  }
  rep.time = time_;
  rep.substeps = sub;
  rep.particles_moved = true;
  rep.min_density = std::numeric_limits<double>::infinity();
  rep.max_density = 0;
  double vmax2 = 0;
  if (fused) {  // (from the last corrector loop)
    rep.min_density = report_rho_min_;
    rep.max_density = report_rho_max_;
    vmax2 = report_vmax2_;
  }
  for (std::size_t i = 0; i < n && !fused; ++i) {
    rep.min_density = std::min(rep.min_density, y_.rho[i]);
    rep.max_density = std::max(rep.max_density, y_.rho[i]);
    if (wall_[i]) continue;
    const double* v = &y_.v[3 * i];
    vmax2 = std::max(vmax2, v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  }
  rep.max_speed = std::sqrt(vmax2);
  if (!bodies_.walls.empty()) rep.body_forces = take_body_forces();
  return rep;
}

double SdpdBackend::general_substep(std::uint64_t step_index, std::uint64_t key, double remaining,
                                    std::uint32_t sub, StepReport& rep) {
  const std::size_t n = mass_.size();
  const int dim = model_.box.dimension;
  species_.set_time(time_);  // the laws of t: at the time of each evaluation
  evaluate(y_, key, r0_, true);
  // (not a structured binding: clang 14 cannot use one in the OpenMP regions below)
  const Substep next = next_substep(limits(y_, r0_), model_.max_time_step, model_.force_time_step,
                                    remaining, rep.stable_dt, rep.limiting_criterion);
  const double dt = next.dt;
  if (sub >= kMaxSubsteps) {
    throw_too_many_substeps(step_index, next.limit_name, next.limit);
  }
  // Transport velocity: the shift v~ - v and the A-tensor term need dt (not in the limits).
  const bool tvf = tvf_;
  if (tvf) apply_transport_velocity(y_, dt, r0_);
  const double sdt = std::sqrt(dt);
  const bool noise_on = !r0_.acc_noise.empty();
  // Predictor: Y~ = Y + dt f(Y). One parallel pass (copy and update; serial copies limited
  // the two-thread speed-up in 2D, ~12 pairs per particle).
  ytmp_.x.resize(3 * n);
  ytmp_.v.resize(3 * n);
  ytmp_.rho.resize(n);
  const bool continuity = model_.density_mode == DensityMode::kContinuity;
  const auto ni = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static) if (ni > kMinParallelLight)
  for (std::int64_t ii = 0; ii < ni; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    for (int a = 0; a < 3; ++a) {
      ytmp_.x[3 * i + a] = y_.x[3 * i + a];
      ytmp_.v[3 * i + a] = y_.v[3 * i + a];
    }
    ytmp_.rho[i] = continuity ? y_.rho[i] + dt * r0_.drho[i] : y_.rho[i];
    if (wall_[i]) continue;
    for (int a = 0; a < dim; ++a) {
      const std::size_t k = 3 * i + a;
      ytmp_.x[k] += tvf ? dt * (y_.v[k] + r0_.shift[k]) : dt * y_.v[k];
      ytmp_.v[k] += dt * r0_.acc[k] + (noise_on ? sdt * r0_.acc_noise[k] : 0.0);
    }
    pbox_.wrap(&ytmp_.x[3 * i]);
  }
  for (std::size_t s = 0; s < y_.c.size(); ++s) {
    ytmp_.c[s] = y_.c[s];
    if (!model_.species[s].deterministic()) continue;
    for (std::size_t i = 0; i < n; ++i) ytmp_.c[s][i] += dt * r0_.dc[s][i];
  }
  species_.set_time(time_ + dt);
  move_bodies(ytmp_, time_ + dt);    // (moving bodies: their walls at the end of the sub-step)
  evaluate(ytmp_, key, r1_, false);  // noise: the start-of-step force is reused
  if (tvf) apply_transport_velocity(ytmp_, dt, r1_);
    // Corrector: Y = Y + dt/2 (f(Y) + f(Y~)), same noise increment.
#pragma omp parallel for schedule(static) if (ni > kMinParallelLight)
  for (std::int64_t ii = 0; ii < ni; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    // (summation density: rho~ is recomputed at the next evaluation anyway)
    y_.rho[i] = continuity ? y_.rho[i] + 0.5 * dt * (r0_.drho[i] + r1_.drho[i]) : ytmp_.rho[i];
    if (wall_[i]) continue;
    for (int a = 0; a < dim; ++a) {
      const std::size_t k = 3 * i + a;
      y_.x[k] += tvf ? 0.5 * dt * ((y_.v[k] + r0_.shift[k]) + (ytmp_.v[k] + r1_.shift[k]))
                     : 0.5 * dt * (y_.v[k] + ytmp_.v[k]);
      y_.v[k] += 0.5 * dt * (r0_.acc[k] + r1_.acc[k]) + (noise_on ? sdt * r0_.acc_noise[k] : 0.0);
    }
    pbox_.wrap(&y_.x[3 * i]);
  }
  for (std::size_t s = 0; s < y_.c.size(); ++s) {
    if (!model_.species[s].deterministic()) continue;
    for (std::size_t i = 0; i < n; ++i) y_.c[s][i] += 0.5 * dt * (r0_.dc[s][i] + r1_.dc[s][i]);
  }
  move_bodies(y_, time_ + dt);
  if (!bodies_.walls.empty()) accumulate_body_forces(dt);
  return dt;
}

}  // namespace sadr::fluid
