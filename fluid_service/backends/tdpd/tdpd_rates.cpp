// SPDX-License-Identifier: MIT
/// \file tdpd_rates.cpp
/// The tDPD pair loop in two passes over the full (sorted) neighbour list:
///  1. per pair (i < j) once: the scalar force factor F_ij / r_ij (conservative, dissipative,
///     random: the expensive pow, Philox and Box-Muller), the flux weight w_DC and the density
///     kernel W, stored in a half-pair array;
///  2. per particle i, a gather over its full list reading the stored pair scalars
///     (F_i = sum_j s_ij (x_i - x_j), dC_i = sum_j kappa w_ij (C_j - C_i), rho_i = sum_j W_ij).
/// Both passes are per-particle loops with a fixed order (no scatter, no atomics), so results
/// are identical on any thread count, and s_ij is one number for both particles, so the pair
/// forces are exactly antisymmetric (total momentum conserved to rounding).
#include <algorithm>
#include <cmath>

#include "sadr/common/rng.hpp"
#include "sadr/fluid/parallel.hpp"
#include "sadr/fluid/tdpd_backend.hpp"
#include "tdpd_forces.hpp"

namespace sadr::fluid {

void TdpdBackend::build_half_pairs() const {
  const std::size_t n = nlist_.size();
  first_gt_.resize(n);
  half_off_.resize(n + 1);
  half_off_[0] = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto nb = nlist_.of(i);
    const auto it = std::upper_bound(nb.begin(), nb.end(), static_cast<std::uint32_t>(i));
    first_gt_[i] = nlist_.offsets[i] + static_cast<std::uint32_t>(it - nb.begin());
    half_off_[i + 1] = half_off_[i] + (nlist_.offsets[i + 1] - first_gt_[i]);
  }
  pair_of_entry_.resize(nlist_.indices.size());
  const auto ni = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static) if (ni >= kMinParallel)
  for (std::int64_t ii = 0; ii < ni; ++ii) {
    const auto i = static_cast<std::uint32_t>(ii);
    for (std::uint32_t e = nlist_.offsets[i]; e < nlist_.offsets[i + 1]; ++e) {
      const std::uint32_t j = nlist_.indices[e];
      if (j > i) {
        pair_of_entry_[e] = half_off_[i] + (e - first_gt_[i]);
      } else {  // the pair is stored with j: find i in j's (sorted) list
        const auto nb = nlist_.of(j);
        const auto it = std::lower_bound(nb.begin(), nb.end(), i);
        const auto ej = nlist_.offsets[j] + static_cast<std::uint32_t>(it - nb.begin());
        pair_of_entry_[e] = half_off_[j] + (ej - first_gt_[j]);
      }
    }
  }
  const std::size_t np = half_off_[n];
  pair_force_.resize(np);
  pair_flux_.resize(np);
  pair_kernel_.resize(np);
}

void TdpdBackend::evaluate(const std::vector<double>& x, const std::vector<double>& v,
                           const std::vector<std::vector<double>>& c, std::uint64_t noise_key,
                           double dt, std::vector<double>& force,
                           std::vector<std::vector<double>>& flux, bool flux_only) {
  ensure_neighbors();
  switch (model_.box.dimension) {
    case 1:
      evaluate_dim<1>(x, v, c, noise_key, dt, force, flux, flux_only);
      break;
    case 2:
      evaluate_dim<2>(x, v, c, noise_key, dt, force, flux, flux_only);
      break;
    default:
      evaluate_dim<3>(x, v, c, noise_key, dt, force, flux, flux_only);
      break;
  }
  if (walls_.enabled()) {
    if (!flux_only) {
      walls_.add_forces(x, v, wall_, model_.seed, noise_key & ~(std::uint64_t{1} << 63),
                        static_cast<std::uint32_t>(noise_key >> 63), dt, force);
    }
    walls_.add_fluxes(x, wall_, species_.transported(), kappa_, c, dt, flux);
  }
  if (buffers_.enabled()) buffers_.zero_inflow_flux(x, species_.transported(), flux);
}

template <int D>
void TdpdBackend::evaluate_dim(const std::vector<double>& x, const std::vector<double>& v,
                               const std::vector<std::vector<double>>& c, std::uint64_t noise_key,
                               double dt, std::vector<double>& force,
                               std::vector<std::vector<double>>& flux, bool flux_only) {
  const auto n = static_cast<std::int64_t>(n_);
  const double rc = model_.smoothing_length;
  const double rc2 = rc * rc;
  const double inv_rc = 1.0 / rc;
  const double rcc2 = r_cc_ * r_cc_;
  const double inv_rcc = 1.0 / r_cc_;
  const double cut2 = flux_only ? rcc2 : rc2;
  const double a = params_.a;
  const double gamma = params_.gamma;
  const double half_s1 = 0.5 * params_.s1;
  // Random force sigma w_R xi / sqrt(dt); sigma = 0 (k_B T = 0) draws nothing.
  const double sigma_dt = sigma_ > 0.0 ? sigma_ / std::sqrt(dt) : 0.0;
  // FluidModel::noise = kUniform: xi = sqrt(3) (2u - 1), zero mean and unit variance (Groot &
  // Warren 1997 use uniform random numbers), one Philox draw and no log/sqrt/cos per pair.
  const bool uniform = model_.noise == NoiseDistribution::kUniform;
  const rng::CounterRng rng{model_.seed};
  const auto sub = static_cast<std::uint32_t>(noise_key >> 63);
  const std::uint64_t key = noise_key & ~(std::uint64_t{1} << 63);
  const auto& transported = species_.transported();
  const auto& g = model_.gravity;
  const auto* idx = nlist_.indices.data();

  // Pass 1: pair scalars for i < j.
#pragma omp parallel for schedule(static) if (n >= kMinParallel)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = static_cast<std::uint32_t>(ii);
    const double* xi = &x[3 * i];
    const double* vi = &v[3 * i];
    std::uint32_t h = half_off_[i];
    for (std::uint32_t e = first_gt_[i]; e < nlist_.offsets[i + 1]; ++e, ++h) {
      const std::uint32_t j = idx[e];
      double d[3] = {0.0, 0.0, 0.0};
      for (int k = 0; k < D; ++k) d[k] = xi[k] - x[3 * j + k];
      pbox_.minimum_image(d);
      double r2 = 0.0;
      for (int k = 0; k < D; ++k) r2 += d[k] * d[k];
      if (r2 >= cut2 || r2 == 0.0) {
        pair_force_[h] = 0.0;
        pair_flux_[h] = 0.0;
        pair_kernel_[h] = 0.0;
        continue;
      }
      const double r = std::sqrt(r2);
      pair_flux_[h] = r2 < rcc2 ? tdpd::flux_weight(r, inv_rcc) : 0.0;
      if (flux_only) continue;
      pair_kernel_[h] = kernel_.w(r);
      const double inv_r = 1.0 / r;
      const auto w = tdpd::weights(r * inv_rc, half_s1);
      double ev = 0.0;
      for (int k = 0; k < D; ++k) ev += d[k] * (vi[k] - v[3 * j + k]);
      ev *= inv_r;
      double fmag = a * w.w_c - gamma * w.w_r * w.w_r * ev;
      if (sigma_dt > 0.0) {
        const double xi_ij =
            uniform ? 1.7320508075688772 *
                          (2.0 * rng.uniform2(rng::Purpose::kPairNoise, key, i, j, sub)[0] - 1.0)
                    : rng.normal2(rng::Purpose::kPairNoise, key, i, j, sub)[0];
        fmag += sigma_dt * w.w_r * xi_ij;
      }
      pair_force_[h] = fmag * inv_r;
    }
  }

  // Pass 2: per-particle gather in list order.
  if (!flux_only) force.assign(3 * n_, 0.0);
  for (auto& q : flux) q.assign(n_, 0.0);
  if (!flux_only) rho_.resize(n_);
#pragma omp parallel for schedule(static) if (n >= kMinParallel)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    double fi[3] = {0.0, 0.0, 0.0};
    double rho = kernel_.w0();
    const double* xi = &x[3 * i];
    const bool wall = wall_[i] != 0;
    for (std::uint32_t e = nlist_.offsets[i]; e < nlist_.offsets[i + 1]; ++e) {
      const std::uint32_t h = pair_of_entry_[e];
      const double w = pair_flux_[h];
      if (!flux_only) {
        const double s = pair_force_[h];
        rho += pair_kernel_[h];
        if (s != 0.0 && !wall) {
          const std::uint32_t j = idx[e];
          double d[3] = {0.0, 0.0, 0.0};
          for (int k = 0; k < D; ++k) d[k] = xi[k] - x[3 * j + k];
          pbox_.minimum_image(d);
          for (int k = 0; k < D; ++k) fi[k] += s * d[k];
        }
      }
      if (w != 0.0 && !wall) {
        const std::uint32_t j = idx[e];
        if (buffers_.enabled() && buffers_.across_seam(xi, &x[3 * j])) continue;
        for (const int sp : transported) {
          if (any_wall_) {
            const auto role = species_.role(sp, j);
            if (role != SpeciesTransport::Role::kFree &&
                role != SpeciesTransport::Role::kDirichlet) {
              continue;
            }
          }
          flux[sp][i] += kappa_[sp] * w * (c[sp][j] - c[sp][i]);
        }
      }
    }
    if (!flux_only) {
      rho_[i] = rho;
      // Frozen wall particles feel no force; their species stay fixed (Dirichlet) or unused.
      for (int k = 0; k < D; ++k) force[3 * i + k] = wall ? 0.0 : fi[k] + g[k];
    }
    if (!wall && species_.has_reactions()) species_.add_reactions(i, c, flux);
  }
  if (!flux_only) rho_valid_ = true;
}

template void TdpdBackend::evaluate_dim<1>(const std::vector<double>&, const std::vector<double>&,
                                           const std::vector<std::vector<double>>&, std::uint64_t,
                                           double, std::vector<double>&,
                                           std::vector<std::vector<double>>&, bool);
template void TdpdBackend::evaluate_dim<2>(const std::vector<double>&, const std::vector<double>&,
                                           const std::vector<std::vector<double>>&, std::uint64_t,
                                           double, std::vector<double>&,
                                           std::vector<std::vector<double>>&, bool);
template void TdpdBackend::evaluate_dim<3>(const std::vector<double>&, const std::vector<double>&,
                                           const std::vector<std::vector<double>>&, std::uint64_t,
                                           double, std::vector<double>&,
                                           std::vector<std::vector<double>>&, bool);

}  // namespace sadr::fluid
