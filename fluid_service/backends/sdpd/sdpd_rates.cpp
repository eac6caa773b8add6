// SPDX-License-Identifier: MIT
/// \file sdpd_rates.cpp
/// The SDPD pair loop: one gather pass over full neighbour lists evaluating
/// SdpdMomentumTerm, ContinuityTerm, PairNoise and DiffusionTerm (pair_terms.hpp), for systems
/// with walls, transported species or reactions; bulk fluids take the half-pair path
/// (sdpd_half_pairs.hpp, each pair once).
#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <span>
#include <string>

#include "sadr/fluid/pair_noise_batch.hpp"
#include "sadr/fluid/parallel.hpp"
#include "sdpd_backend.hpp"
#include "sdpd_half_pairs.hpp"

namespace sadr::fluid {

void SdpdBackend::evaluate(Y& y, std::uint64_t noise_step, Rates& out, bool with_noise) {
  prepared_ = false;  // hin_/hacc_ are reused below
  switch (model_.box.dimension) {
    case 1:
      evaluate_dim<1>(y, noise_step, out, with_noise);
      break;
    case 2:
      evaluate_dim<2>(y, noise_step, out, with_noise);
      break;
    default:
      evaluate_dim<3>(y, noise_step, out, with_noise);
      break;
  }
}

template <int D>
SdpdPairParams SdpdBackend::make_pair_params(bool noise_on) const {
  // (the same expressions as the terms of evaluate_dim)
  const double h = kernel_.support();
  const double h2 = h * h;
  const double c_d = 2.0 * (D + 2) / (D + 3);
  const SdpdMomentumTerm momentum{c_d * model_.shear_viscosity};
  const ContinuityTerm continuity{model_.density_diffusion * h * model_.sound_speed, 0.01 * h2};
  SdpdPairParams pp;
  pp.inv_h = kernel_.inv_support();
  pp.f_coef = kernel_.f_coef();
  pp.sqrt_f_coef = kernel_.sqrt_f_coef();
  pp.lucy = kernel_.type() == KernelType::kLucy;
  pp.friction = momentum.friction;
  pp.delta_h_c0 = continuity.delta_h_c0;
  pp.eps_h2 = continuity.eps_h2;
  pp.noise_amp = std::sqrt(2.0 * model_.temperature * c_d * model_.shear_viscosity);
  pp.noise = noise_on;
  return pp;
}

template <int D>
void SdpdBackend::evaluate_dim(Y& y, std::uint64_t noise_step, Rates& out, bool with_noise) {
  const std::size_t n = mass_.size();
  const auto ni = static_cast<std::int64_t>(n);
  const double h = kernel_.support();
  const double h2 = h * h;
  const bool noise_on = with_noise && model_.temperature > 0;
  const bool summation = model_.density_mode == DensityMode::kSummation;
  ensure_neighbors(y.x);
  const bool half = half_ok_ && slab_count_ > 0;  // no walls, species or reactions: pairs once

  // (the half path sums into hacc_ and writes every entry of acc, acc_noise and drho at the end)
  if (half) {
    out.acc.resize(3 * n);
    out.acc_noise.resize(noise_on ? 3 * n : 0);
    out.drho.resize(n);
  } else {
    out.acc.assign(3 * n, 0.0);
    if (noise_on) {
      out.acc_noise.assign(3 * n, 0.0);
    } else {
      out.acc_noise.clear();
    }
    out.drho.assign(n, 0.0);
  }
  out.dc.resize(y.c.size());
  for (auto& d : out.dc) d.assign(n, 0.0);

  const double* x = y.x.data();
  auto geometry = [&](std::size_t i, std::uint32_t j, PairGeometry<D>& g) -> bool {
    double d[3] = {x[3 * i] - x[3 * j], x[3 * i + 1] - x[3 * j + 1], x[3 * i + 2] - x[3 * j + 2]};
    pbox_.minimum_image(d);
    double r2 = 0;
    for (int a = 0; a < D; ++a) {
      g.x[a] = d[a];
      r2 += d[a] * d[a];
    }
    if (r2 >= h2) return false;
    g.r2 = r2;
    g.r = std::sqrt(r2);
    g.f = kernel_.f(g.r);
    g.inv_r2 = 1.0 / r2;
    return true;
  };

  // Summation density (SPEC eq 19) replaces the integrated one (fluid particles).
  if (summation && half_ok_) {
    summation_half<D>(y);
  } else if (summation) {
#pragma omp parallel for schedule(static) if (ni > kMinParallel)
    for (std::int64_t ii = 0; ii < ni; ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      // wall layers have truncated support: keep their initial density; buffers: prescribed
      if (wall_[i] || buffer_[i]) continue;
      double rho = mass_[i] * kernel_.w0();
      PairGeometry<D> g{};
      for (const std::uint32_t j : nlist_.of(i)) {
        if (geometry(i, j, g)) rho += mass_[j] * kernel_.w(g.r);
      }
      y.rho[i] = rho;
    }
  }
  if (half) {
    hin_.resize(n);
    hacc_.resize(n);
#pragma omp parallel for schedule(static) if (ni > kMinParallelLight)
    for (std::int64_t ii = 0; ii < ni; ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      fill_half_in(i, y, noise_on);
      hacc_[i] = HalfAcc{};
    }
  } else {
    pd2_.resize(n);
    inv_nd_.resize(n);
    vol_.resize(n);
    if (noise_on) sqrt_inv_nd_.resize(n);
#pragma omp parallel for schedule(static) if (ni > kMinParallelLight)
    for (std::int64_t ii = 0; ii < ni; ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      const double nd_inv = mass_[i] / y.rho[i];  // 1/d_i
      inv_nd_[i] = nd_inv;
      pd2_[i] = eos_.pressure(y.rho[i]) * nd_inv * nd_inv;
      vol_[i] = mass_[i] / y.rho[i];
      if (noise_on) sqrt_inv_nd_[i] = std::sqrt(nd_inv);
    }
  }

  // a = b = c_D eta with c_D = 2(D+2)/(D+3): 5/3 in 3D (LAMMPS, Espanol-Revenga with zeta = 0),
  // 8/5 in 2D, 3/2 in 1D, so that the continuum limit has shear viscosity eta in every dimension
  // (see docs/fluid-core.md; LAMMPS' 5/3 in 2D gives 1.042 eta).
  const double c_d = 2.0 * (D + 2) / (D + 3);
  const SdpdMomentumTerm momentum{c_d * model_.shear_viscosity};
  const ContinuityTerm continuity{model_.density_diffusion * h * model_.sound_speed, 0.01 * h2};
  const DiffusionTerm diffusion{model_.diffusion_eps * h2};
  scratch_.resize(static_cast<std::size_t>(max_threads()));
  const double noise_amp = std::sqrt(2.0 * model_.temperature * c_d * model_.shear_viscosity);
  const bool species_on = !species_.transported().empty();
  const auto& bq = model_.boussinesq;
  double max_k_sum = 0, max_visc = 0;
  const SdpdPairParams pair_params = make_pair_params<D>(noise_on);

  if (half) {
    evaluate_half<D>(y, noise_step, out, noise_on, pair_params, c_d);
    return;
  }
#pragma omp parallel if (ni > kMinParallel)
  {
    // Per-thread scratch: a particle's pairs within h as a SIMD block (sdpd_pair_block.hpp);
    // the noise numbers of a whole neighbour list are generated at once (pair_noise_batch.hpp).
    // Per-pair results are summed in neighbour order (thread-count independent).
    PairScratch& sc = scratch_[static_cast<std::size_t>(thread_index())];
    SdpdPairBlock& b = sc.block;
#pragma omp for schedule(static) reduction(max : max_k_sum, max_visc)
    for (std::int64_t ii = 0; ii < ni; ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      const bool wall_i = wall_[i] != 0;
      std::array<double, D> force{};
      double drho = 0, k_sum = 0, f_sum = 0;
      std::size_t npairs = 0;
      sc.reserve(nlist_.of(i).size());
      const double* vi = &y.v[3 * i];
      PairGeometry<D> g{};
      if (!wall_i && !morris_) {
        // Fast path (fluid particle, stationary walls): gather, SIMD pair terms, ordered sums.
        const double* xi = &x[3 * i];
        std::size_t m = 0;
        for (const std::uint32_t j : nlist_.of(i)) {
          double d[D];
          const double r2 = pbox_.offset_first<D>(xi, &x[3 * j], d);
          if (r2 >= h2) continue;
          b.j[m] = j;
          for (int a = 0; a < D; ++a) {
            b.x[a][m] = d[a];
            b.v[a][m] = vi[a] - y.v[3 * j + a];
          }
          b.r2[m] = r2;
          b.pd2_j[m] = pd2_[j];
          b.inv_nd_j[m] = inv_nd_[j];
          b.m_j[m] = mass_[j];
          b.vol_j[m] = vol_[j];
          b.rho_j[m] = y.rho[j];
          if (noise_on) b.sqrt_inv_nd_j[m] = sqrt_inv_nd_[j];
          ++m;
        }
        sdpd_pair_block<D>(pair_params,
                           {static_cast<std::uint32_t>(i), pd2_[i], inv_nd_[i], y.rho[i],
                            noise_on ? sqrt_inv_nd_[i] : 0.0},
                           m, b);
        for (std::size_t k = 0; k < m; ++k) {
          for (int a = 0; a < D; ++a) force[a] += b.force[a][k];
          f_sum += b.f[k] * b.inv_nd_j[k];
        }
        if (!summation) {
          for (std::size_t k = 0; k < m; ++k) drho += b.drho[k];
        }
        if (species_on) {
          for (std::size_t k = 0; k < m; ++k) {
            for (int a = 0; a < D; ++a) g.x[a] = b.x[a][k];
            g.r2 = b.r2[k];
            g.r = b.r[k];
            g.f = b.f[k];
            g.inv_r2 = 1.0 / g.r2;
            const double kk = diffusion.coefficient(g, b.vol_j[k]);
            k_sum += kk;
            double xij[3] = {0.0, 0.0, 0.0};
            for (int a = 0; a < D; ++a) xij[a] = g.x[a];
            species_.add_pair(i, b.j[k], kk, xij, y.c, out.dc);
          }
        }
        npairs = noise_on ? m : 0;
      }
      for (const std::uint32_t j :
           (!wall_i && !morris_) ? std::span<const std::uint32_t>{} : nlist_.of(i)) {
        if (!geometry(i, j, g)) continue;
        std::array<double, D> v;
        for (int a = 0; a < D; ++a) v[a] = vi[a] - y.v[3 * j + a];
        if (!summation) drho += continuity.with_volume(g, v, mass_[j], vol_[j], y.rho[i], y.rho[j]);
        if (wall_i) {  // walls: density only, plus species on WallCondition::kFree walls
          if (species_on && species_.active_wall(i)) {
            const double k = diffusion.coefficient(g, vol_[j]);
            k_sum += k;
            double xij[3] = {0.0, 0.0, 0.0};
            for (int a = 0; a < D; ++a) xij[a] = g.x[a];
            species_.add_pair_wall(i, j, k, xij, y.c, out.dc);
          }
          continue;
        }
        if (morris_ && wall_region_[j] >= 0) {
          // Morris et al. 1997 extrapolated wall velocity: v_ij = beta v_i in the viscous term.
          const auto& reg = model_.wall_regions[static_cast<std::size_t>(wall_region_[j])];
          double di = 0;
          for (int a = 0; a < 3; ++a)
            di += reg.inward_normal[a] * (x[3 * i + a] - reg.surface_point[a]);
          const double beta = std::min(1.5, 1.0 + wall_depth_[j] / std::max(di, 1e-3 * h));
          std::array<double, D> vb;
          for (int a = 0; a < D; ++a) vb[a] = beta * vi[a];
          const SdpdMomentumTerm pressure_only{0.0};
          pressure_only(g, pd2_[i], pd2_[j], inv_nd_[i] * inv_nd_[j], v, force);
          const SdpdMomentumTerm viscous_only{momentum.friction};
          viscous_only(g, 0.0, 0.0, inv_nd_[i] * inv_nd_[j], vb, force);
        } else {
          momentum(g, pd2_[i], pd2_[j], inv_nd_[i] * inv_nd_[j], v, force);
        }
        f_sum += g.f * inv_nd_[j];
        if (noise_on) {
          // force_i = sign sqrt(amp2/2) (z0, z1, z2) + sqrt(amp2/2)/r x_ij z3 (PairNoise::add)
          // sqrt(amp2/2) = sqrt(2 k_B T c_D eta) sqrt(F_ij) sqrt(1/d_i) sqrt(1/d_j), the last
          // product formed symmetrically so both sides of the pair get the same value.
          const double amp =
              (noise_amp * kernel_.sqrt_f(g.r)) * (sqrt_inv_nd_[i] * sqrt_inv_nd_[j]);
          b.j[npairs] = j;
          b.amp[npairs] = i < j ? amp : -amp;
          b.amp_r[npairs] = amp / g.r;
          for (int a = 0; a < D; ++a) b.x[a][npairs] = g.x[a];
          ++npairs;
        }
        if (species_on) {
          const double k = diffusion.coefficient(g, vol_[j]);
          k_sum += k;
          double xij[3] = {0.0, 0.0, 0.0};
          for (int a = 0; a < D; ++a) xij[a] = g.x[a];
          species_.add_pair(i, j, k, xij, y.c, out.dc);
        }
      }
      out.drho[i] = drho;
      if (open_ && buffer_[i]) {  // inlet/outlet: no forces, no noise, density set after
        out.drho[i] = 0.0;        // each sub-step (apply_open_boundary)
        if (species_on) {
          max_k_sum = std::max(max_k_sum, k_sum);
          species_.add_reactions(i, y.c, out.dc);
        }
        continue;
      }
      if (wall_i) {
        if (species_on && species_.active_wall(i)) {
          max_k_sum = std::max(max_k_sum, k_sum);
          species_.add_reactions(i, y.c, out.dc);
        }
        continue;
      }
      max_k_sum = std::max(max_k_sum, k_sum);
      max_visc = std::max(max_visc, f_sum / y.rho[i]);
      const double inv_m = 1.0 / mass_[i];
      double body[3] = {model_.gravity[0], model_.gravity[1], model_.gravity[2]};
      if (bq.species >= 0) {
        const double bqa = bq.coefficient * (y.c[bq.species][i] - bq.reference);
        for (int a = 0; a < 3; ++a) body[a] += bqa * bq.direction[a];
      }
      for (int a = 0; a < D; ++a) out.acc[3 * i + a] = force[a] * inv_m + body[a];
      if (noise_on) {
        pair_noise_numbers(model_.seed, noise_step, static_cast<std::uint32_t>(i), b.j.data(),
                           npairs, model_.noise, sc.z[0].data(), sc.z[1].data(), sc.z[2].data(),
                           sc.z[3].data());
        std::array<double, D> fnoise{};
        const float* z3 = sc.z[3].data();
        for (std::size_t k = 0; k < npairs; ++k) {
          const double s3 = b.amp_r[k] * static_cast<double>(z3[k]);
          for (int a = 0; a < D; ++a) {
            fnoise[a] += b.amp[k] * static_cast<double>(sc.z[a][k]) + s3 * b.x[a][k];
          }
        }
        for (int a = 0; a < D; ++a) out.acc_noise[3 * i + a] = fnoise[a] * inv_m;
      }
      if (species_on) species_.add_reactions(i, y.c, out.dc);
    }
  }  // omp parallel
  out.max_k_sum = max_k_sum;
  out.max_visc_sum = 2.0 * c_d * max_visc;  // (a + b)/rho_i sum_j V_j F_ij
}

void SdpdBackend::prepare_half(bool noise_on) {
  const std::size_t n = mass_.size();
  const auto ni = static_cast<std::int64_t>(n);
  hin_.resize(n);
  hacc_.resize(n);
  const bool have_list = list_ref_x_.size() == y_.x.size();
  int moved = have_list ? 0 : 1;
#pragma omp parallel for schedule(static) if (ni > kMinParallelLight) reduction(max : moved)
  for (std::int64_t ii = 0; ii < ni; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    fill_half_in(i, y_, noise_on);
    hacc_[i] = HalfAcc{};
    if (have_list && moved_since_build(i, &y_.x[3 * i])) moved = 1;
  }
  y_moved_ = moved != 0;
  prepared_ = true;
}

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
  if (scratch_.size() < static_cast<std::size_t>(max_threads()))
    scratch_.resize(static_cast<std::size_t>(max_threads()));
  r0_.acc.resize(3 * n);
  r0_.acc_noise.resize(noise_on ? 3 * n : 0);
  r0_.drho.resize(n);
  r0_.dc.resize(y_.c.size());
  for (auto& d : r0_.dc) d.assign(n, 0.0);
  ytmp_.x.resize(3 * n);
  ytmp_.v.resize(3 * n);
  ytmp_.rho.resize(n);
  const SdpdPairParams pp0 = make_pair_params<D>(noise_on), pp1 = make_pair_params<D>(false);
  const double c_d = 2.0 * (D + 2) / (D + 3);
  const auto& bq = model_.boussinesq;
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
  next_slab_pass();
#pragma omp parallel if (ni > kMinParallel)
  {
    FusedPartial& pt = fused_partials_[static_cast<std::size_t>(thread_index())];
    half_pairs_team<D>(
        y_, key, noise_on, pp0, [&](const std::uint32_t* first, const std::uint32_t* last) {
          for (; first != last; ++first) {
            const std::size_t i = *first;
            half_rates<D>(i, y_, noise_on, &r0_.acc[3 * i],
                          noise_on ? &r0_.acc_noise[3 * i] : nullptr, &r0_.drho[i], pt.max_visc);
            // limits() at y_ (no wall particles on this path)
            const double* v = &y_.v[3 * i];
            pt.vmax2 = std::max(pt.vmax2, v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
            pt.rho_min = std::min(pt.rho_min, y_.rho[i]);
            double a[3] = {model_.gravity[0], model_.gravity[1], model_.gravity[2]};
            if (bq.species >= 0) {
              const double b = bq.coefficient * (y_.c[bq.species][i] - bq.reference);
              for (int k = 0; k < 3; ++k) a[k] += b * bq.direction[k];
            }
            pt.amax2 = std::max(pt.amax2, a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
          }
        });
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
          throw NumericalFailure("sdpd: more than 65535 sub-steps needed in one advance (limit '" +
                                     s.limit_name + "' = " + format_value(s.limit) +
                                     "); use a smaller coupling time_step",
                                 {{"step", std::to_string(step_index)}, {"limit", s.limit_name}});
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
  const double sdt = std::sqrt(dt);
  for (std::size_t s = 0; s < y_.c.size(); ++s) {
    ytmp_.c[s] = y_.c[s];
    if (!model_.species[s].deterministic) continue;
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
  next_slab_pass();
#pragma omp parallel if (ni > kMinParallel)
  {
    FusedPartial& pt = fused_partials_[static_cast<std::size_t>(thread_index())];
    half_pairs_team<D>(
        ytmp_, key, false, pp1, [&](const std::uint32_t* first, const std::uint32_t* last) {
          for (; first != last; ++first) {
            const std::size_t i = *first;
            double acc1[3], drho1, unused = 0;
            half_rates<D>(i, ytmp_, false, acc1, nullptr, &drho1, unused);
            y_.rho[i] = y_.rho[i] + 0.5 * dt * (r0_.drho[i] + drho1);
            for (int a = 0; a < D; ++a) {
              const std::size_t k = 3 * i + a;
              y_.x[k] += 0.5 * dt * (y_.v[k] + ytmp_.v[k]);
              y_.v[k] +=
                  0.5 * dt * (r0_.acc[k] + acc1[a]) + (noise_on ? sdt * r0_.acc_noise[k] : 0.0);
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
        });
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
    if (!model_.species[s].deterministic) continue;
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
template void SdpdBackend::evaluate_dim<1>(Y&, std::uint64_t, Rates&, bool);
template void SdpdBackend::evaluate_dim<2>(Y&, std::uint64_t, Rates&, bool);
template void SdpdBackend::evaluate_dim<3>(Y&, std::uint64_t, Rates&, bool);

}  // namespace sadr::fluid
