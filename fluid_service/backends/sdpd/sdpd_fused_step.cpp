// SPDX-License-Identifier: MIT
/// \file sdpd_fused_step.cpp
/// SdpdBackend::fused_substep: the bulk-fluid (half path, continuity density) sub-step with the
/// per-particle work of the predictor, the corrector, the limits and the health check done in
/// the two parallel regions of its pair loops.
#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <string>

#include "sadr/common/status.hpp"
#include "sadr/fluid/parallel.hpp"
#include "sdpd_backend.hpp"

namespace sadr::fluid {

// The operations (and their order per particle) are those of advance()'s general sub-step:
// evaluate(y_) with noise, limits(), the predictor, evaluate(ytmp_) without noise, the
// corrector, check_health(): the per-particle loops run inside the two parallel regions of the
// pair loops instead of a dozen regions of their own (fork/join and barrier waits were 12-15 %
// of the CPU time with two threads). Bit-identical to the general sub-step.
template <int D>
double SdpdBackend::fused_substep(std::uint64_t step_index, std::uint64_t key, double remaining,
                                  std::uint32_t sub, StepReport& rep, bool& unhealthy) {
  const std::size_t n = mass_.size();
  const auto ni = static_cast<std::int64_t>(n);
  const bool noise_on = model_.temperature > 0;
  if (!prepared_) prepare_half(noise_on);
  prepared_ = false;
  if (y_moved_) rebuild_neighbors(y_.x);
  ensure_scratch();
  r0_.acc.resize(3 * n);
  r0_.acc_noise.resize(noise_on ? 3 * n : 0);
  r0_.drho.resize(n);
  r0_.dc.resize(y_.c.size());
  for (auto& d : r0_.dc) d.assign(n, 0.0);
  ytmp_.x.resize(3 * n);
  ytmp_.v.resize(3 * n);
  ytmp_.rho.resize(n);
  const SdpdPairParams pp0 = make_pair_params<D>(noise_on), pp1 = make_pair_params<D>(false);
  const double c_d = sdpd::viscosity_factor<D>();
  const double stable0 = rep.stable_dt;
  const std::string criterion0 = rep.limiting_criterion;
  int moved = 0;
  double dt = 0;
  std::exception_ptr error;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // per-thread maxima/minima (exact, so combining them in any order gives the same values)
  fused_partials_.assign(static_cast<std::size_t>(max_threads()), FusedPartial{});
  // --- first force evaluation (y_, with noise), limits, predictor (also: hin_ for ytmp_, the
  // list displacement check of the predicted positions)
  slabs_.next_pass();
  species_.set_time(time_);  // the laws of t: at the time of each evaluation
#pragma omp parallel if (ni > kMinParallel)
  {
    FusedPartial& pt = fused_partials_[static_cast<std::size_t>(thread_index())];
    auto after0 = [&](const std::uint32_t* first, const std::uint32_t* last) {
      for (; first != last; ++first) {
        const std::size_t i = *first;
        half_rates<D>(i, y_, noise_on, &r0_.acc[3 * i], noise_on ? &r0_.acc_noise[3 * i] : nullptr,
                      &r0_.drho[i], pt.max_visc);
        // limits() at y_ (no wall particles on this path)
        const double* v = &y_.v[3 * i];
        pt.vmax2 = std::max(pt.vmax2, v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        pt.rho_min = std::min(pt.rho_min, y_.rho[i]);
        double a[3];
        body_acceleration(i, y_.c, a);
        pt.amax2 = std::max(pt.amax2, a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
      }
    };
    half_pairs_team<D>(y_, key, noise_on, pp0, SlabMembersFn(after0));
#pragma omp barrier
    double max_visc = 0, vmax2 = 0, amax2 = 0, rho_min = kInf;
    for (const FusedPartial& q : fused_partials_) {
      max_visc = std::max(max_visc, q.max_visc);
      vmax2 = std::max(vmax2, q.vmax2);
      amax2 = std::max(amax2, q.amax2);
      rho_min = std::min(rho_min, q.rho_min);
    }
    // Every thread computes the sub-step from the reduced values (a pure function: the same
    // result everywhere), which saves the barrier of an `omp single`.
    bool ok = true;
    double my_dt = 0;
    {
      double stable = stable0;
      std::string criterion = criterion0;
      try {
        const Substep s = next_substep(
            limits_from(vmax2, rho_min, amax2, 2.0 * c_d * max_visc, 0.0, y_), model_.max_time_step,
            model_.force_time_step, remaining, stable, criterion);
        if (sub >= kMaxSubsteps) {
          throw_too_many_substeps(step_index, s.limit_name, s.limit);
        }
        my_dt = s.dt;
      } catch (...) {
        ok = false;
        if (thread_index() == 0) error = std::current_exception();
      }
      if (ok && thread_index() == 0) {
        rep.stable_dt = stable;
        rep.limiting_criterion = criterion;
        dt = my_dt;
      }
    }
    if (ok) {  // (the same on every thread)
      const double sdt = std::sqrt(my_dt);
#pragma omp for schedule(static) reduction(max : moved) nowait
      for (std::int64_t ii = 0; ii < ni; ++ii) {
        const auto i = static_cast<std::size_t>(ii);
        for (int a = 0; a < 3; ++a) {
          ytmp_.x[3 * i + a] = y_.x[3 * i + a];
          ytmp_.v[3 * i + a] = y_.v[3 * i + a];
        }
        ytmp_.rho[i] = y_.rho[i] + my_dt * r0_.drho[i];
        for (int a = 0; a < D; ++a) {
          const std::size_t k = 3 * i + a;
          ytmp_.x[k] += my_dt * y_.v[k];
          ytmp_.v[k] += my_dt * r0_.acc[k] + (noise_on ? sdt * r0_.acc_noise[k] : 0.0);
        }
        pbox_.wrap(&ytmp_.x[3 * i]);
        fill_half_in(i, ytmp_, false);  // the second evaluation has no noise
        hacc_[i] = HalfAcc{};
        if (moved_since_build(i, &ytmp_.x[3 * i])) moved = 1;
      }
    }
  }  // omp parallel
  if (error) std::rethrow_exception(error);
  species_.set_time(time_ + dt);
  const double sdt = std::sqrt(dt);
  for (std::size_t s = 0; s < y_.c.size(); ++s) {
    ytmp_.c[s] = y_.c[s];
    if (!model_.species[s].deterministic()) continue;
    for (std::size_t i = 0; i < n; ++i) ytmp_.c[s][i] += dt * r0_.dc[s][i];
  }
  if (moved != 0) rebuild_neighbors(ytmp_.x);
  r1_.dc.resize(y_.c.size());
  for (auto& d : r1_.dc) d.assign(n, 0.0);
  // --- second force evaluation (ytmp_, no noise), corrector, health check, the report's
  // extremes, and for the next sub-step: hin_ for y_ and the list displacement check
  const bool health = y_.c.empty();  // (with species, check_health runs after their corrector)
  const double band = model_.density_band, rho0 = model_.reference_density;
  fused_partials_.assign(fused_partials_.size(), FusedPartial{});
  slabs_.next_pass();
#pragma omp parallel if (ni > kMinParallel)
  {
    FusedPartial& pt = fused_partials_[static_cast<std::size_t>(thread_index())];
    auto after1 = [&](const std::uint32_t* first, const std::uint32_t* last) {
      for (; first != last; ++first) {
        const std::size_t i = *first;
        double acc1[3], drho1, unused = 0;
        half_rates<D>(i, ytmp_, false, acc1, nullptr, &drho1, unused);
        y_.rho[i] = y_.rho[i] + 0.5 * dt * (r0_.drho[i] + drho1);
        for (int a = 0; a < D; ++a) {
          const std::size_t k = 3 * i + a;
          y_.x[k] += 0.5 * dt * (y_.v[k] + ytmp_.v[k]);
          y_.v[k] += 0.5 * dt * (r0_.acc[k] + acc1[a]) + (noise_on ? sdt * r0_.acc_noise[k] : 0.0);
        }
        pbox_.wrap(&y_.x[3 * i]);
        if (health) {  // check_health()'s test
          bool good = std::fabs(y_.rho[i] / rho0 - 1.0) <= band && pbox_.inside(&y_.x[3 * i]);
          for (int a = 0; a < 3; ++a)
            good = good && std::isfinite(y_.x[3 * i + a]) && std::isfinite(y_.v[3 * i + a]);
          if (!good) pt.bad = 1;
        }
        pt.rho_min = std::min(pt.rho_min, y_.rho[i]);
        pt.rho_max = std::max(pt.rho_max, y_.rho[i]);
        const double* v = &y_.v[3 * i];
        pt.vmax2 = std::max(pt.vmax2, v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        fill_half_in(i, y_, noise_on);
        hacc_[i] = HalfAcc{};
        if (moved_since_build(i, &y_.x[3 * i])) pt.moved = 1;
      }
    };
    half_pairs_team<D>(ytmp_, key, false, pp1, SlabMembersFn(after1));
  }  // omp parallel
  bool bad = false, moved_y = false;
  double rmin = kInf, rmax = 0, vmax2_end = 0;
  for (const FusedPartial& q : fused_partials_) {
    bad = bad || q.bad != 0;
    moved_y = moved_y || q.moved != 0;
    rmin = std::min(rmin, q.rho_min);
    rmax = std::max(rmax, q.rho_max);
    vmax2_end = std::max(vmax2_end, q.vmax2);
  }
  for (std::size_t s = 0; s < y_.c.size(); ++s) {
    if (!model_.species[s].deterministic()) continue;
    for (std::size_t i = 0; i < n; ++i) y_.c[s][i] += 0.5 * dt * (r0_.dc[s][i] + r1_.dc[s][i]);
  }
  y_moved_ = moved_y;
  prepared_ = true;
  report_rho_min_ = rmin;
  report_rho_max_ = rmax;
  report_vmax2_ = vmax2_end;
  unhealthy = !health || bad;
  return dt;
}

template double SdpdBackend::fused_substep<1>(std::uint64_t, std::uint64_t, double, std::uint32_t,
                                              StepReport&, bool&);
template double SdpdBackend::fused_substep<2>(std::uint64_t, std::uint64_t, double, std::uint32_t,
                                              StepReport&, bool&);
template double SdpdBackend::fused_substep<3>(std::uint64_t, std::uint64_t, double, std::uint32_t,
                                              StepReport&, bool&);

}  // namespace sadr::fluid
