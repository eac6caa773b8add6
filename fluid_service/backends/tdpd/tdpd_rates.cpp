// SPDX-License-Identifier: MIT
/// \file tdpd_rates.cpp
/// The tDPD pair loop over a half ("forward") neighbour list: every pair is evaluated ONCE and
/// writes +F to i and -F to j (likewise the density kernel and the species fluxes).
///
/// Determinism without atomics: the core SlabScheduler (slab_scheduler.hpp), shared with the SDPD
/// half-pair path. The list (tdpd_cells.hpp) keeps j in the same slab (a layer of cells along the
/// last axis) with j > i, or 1..2 slabs ahead, so a pair spans at most 3 consecutive slabs, and
/// each particle receives its contributions in an order fixed by (phase, slab, member, list
/// entry): independent of the thread count. The slabs and list order depend on the positions at
/// the last list build, which the state blob stores, so restarts stay bit-exact. One number s_ij =
/// F_ij / r_ij serves both particles, so the pair forces are exact negatives (total momentum
/// conserved to rounding); the species fluxes are
/// +-w (C_j - C_i) per pair (total amount conserved to rounding).
///
/// Per particle i: (1) minimum image and r^2 of every forward entry, compacted branch-free to
/// the pairs within the cutoff; (2) their velocity differences; (3) the thermal noise of the
/// block (core pair_noise_numbers: Philox and Box-Muller in SIMD lanes); (4) the pair scalars
/// (tdpd::pair_scalars, SIMD); (5) one scatter pass. Species are packed particle-major for the
/// duration of the evaluation, so the per-pair species loop is contiguous.
#include <algorithm>
#include <cmath>
#include <string>

#include "sadr/common/status.hpp"
#include "sadr/fluid/pair_noise_batch.hpp"
#include "sadr/fluid/parallel.hpp"
#include "tdpd_backend.hpp"
#include "tdpd_forces.hpp"
#include "tdpd_pair_block.hpp"

namespace sadr::fluid {

void TdpdBackend::rebuild_neighbors(const std::vector<double>& ref) const {
  tdpd::build_half_list(pbox_, builder_->cutoff(), ref, half_);
  slabs_.set(std::move(half_.slabs), half_.list);
  list_ref_x_ = ref;
  ++list_builds_;
}

template <class PerParticle>
void TdpdBackend::slab_phases(PerParticle&& per_particle) const {
  std::vector<tdpd::PairBlock> blocks(static_cast<std::size_t>(max_threads()));
  slabs_.run(
      [&](const std::uint32_t* first, const std::uint32_t* last, std::size_t t) {
        tdpd::PairBlock& block = blocks[t];
        block.reserve(half_.max_len);
        for (; first != last; ++first) per_particle(*first, block);
      },
      static_cast<std::int64_t>(n_) >= kMinParallel);
}

void TdpdBackend::evaluate(const std::vector<double>& x, const std::vector<double>& v,
                           const std::vector<std::vector<double>>& c, std::uint64_t noise_key,
                           double dt, std::vector<double>& force,
                           std::vector<std::vector<double>>& flux, bool flux_only,
                           bool dirichlet_rate) {
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
    walls_.add_fluxes(x, wall_, species_.transported(), kappa_, c, flux, dirichlet_rate);
  }
  if (buffers_.enabled()) buffers_.zero_inflow_flux(x, species_.transported(), flux);
}

template <int D>
void TdpdBackend::evaluate_dim(const std::vector<double>& x, const std::vector<double>& v,
                               const std::vector<std::vector<double>>& c, std::uint64_t noise_key,
                               double dt, std::vector<double>& force,
                               std::vector<std::vector<double>>& flux, bool flux_only) {
  const std::size_t n = n_;
  const auto ni = static_cast<std::int64_t>(n);
  const double rc = model_.smoothing_length;
  const double cut2 = flux_only ? r_cc_ * r_cc_ : rc * rc;
  tdpd::PairConsts pc{};
  pc.inv_rc = 1.0 / rc;
  pc.rcc2 = r_cc_ * r_cc_;
  pc.inv_rcc = 1.0 / r_cc_;
  pc.a = params_.a;
  pc.gamma = params_.gamma;
  pc.half_s1 = 0.5 * params_.s1;
  // Random force sigma w_R xi / sqrt(dt); sigma = 0 (k_B T = 0) draws nothing.
  pc.sigma_dt = sigma_ > 0.0 ? sigma_ / std::sqrt(dt) : 0.0;
  pc.kernel_w0 = kernel_.w0();
  const bool noise = !flux_only && pc.sigma_dt > 0.0;
  // The noise of (seed, key, min(i,j), max(i,j)): Philox words 0, 1 give z[0] (the regular
  // evaluation), words 2, 3 give z[2] (the initial evaluation after initialize/restore, flagged
  // in bit 63 of the key), so the two never share a number. kUniform: unit-variance uniform.
  const bool initial = (noise_key >> 63) != 0;
  const std::uint64_t key = noise_key & ~(std::uint64_t{1} << 63);
  const auto& transported = species_.transported();
  const std::size_t nt = transported.size();
  const bool buffers = buffers_.enabled();

  // Particle-major species: cp[i nt + t] = C, qp the flux sums; okp = 1 where the pair term
  // from that particle counts (wall roles free / Dirichlet), 0 else (only with walls).
  cp_.resize(n * nt);
  qp_.assign(n * nt, 0.0);
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& cs = c[static_cast<std::size_t>(transported[t])];
    for (std::size_t i = 0; i < n; ++i) cp_[i * nt + t] = cs[i];
  }
  if (any_wall_) {
    okp_.resize(n * nt);
    for (std::size_t t = 0; t < nt; ++t) {
      for (std::size_t i = 0; i < n; ++i) {
        const auto role = species_.role(transported[t], i);
        okp_[i * nt + t] =
            role == SpeciesTransport::Role::kFree || role == SpeciesTransport::Role::kDirichlet
                ? 1.0
                : 0.0;
      }
    }
  }
  fsum_.assign(flux_only ? 0 : 3 * n, 0.0);
  if (!flux_only) rho_.assign(n, kernel_.w0());
  const double* xp = x.data();
  const double* vp = v.data();
  const double* cpp = cp_.data();
  const double* okpp = any_wall_ ? okp_.data() : nullptr;
  double* fp = fsum_.data();
  double* qpp = qp_.data();
  double* rhop = rho_.data();

  slab_phases([&](std::uint32_t i, tdpd::PairBlock& b) {
    const double* xi = &xp[3 * i];
    std::uint32_t* __restrict bj = b.j.data();
    double* __restrict bd[3] = {b.d[0].data(), b.d[1].data(), b.d[2].data()};
    double* __restrict br2 = b.r2.data();
    std::size_t m = 0;
    // (1) compaction: each entry is written at slot m, m advances if 0 < r < cutoff (the
    // cut-off branch is unpredictable: about half the entries lie in the skin)
    for (const std::uint32_t j : half_.list.of(i)) {
      double d[D];
      const double r2 = pbox_.offset_first<D>(xi, &xp[3 * j], d);
      bj[m] = j;
      for (int k = 0; k < D; ++k) bd[k][m] = d[k];
      br2[m] = r2;
      m += ((r2 < cut2) & (r2 > 0.0)) ? 1 : 0;
    }
    if (m == 0) return;
    // (2) velocity differences of the accepted pairs
    if (!flux_only) {
      const double* vi = &vp[3 * i];
      for (int k = 0; k < D; ++k) {
        double* __restrict dv = b.dv[k].data();
        for (std::size_t p = 0; p < m; ++p) dv[p] = vi[k] - vp[3 * bj[p] + k];
      }
    }
    // (3) noise, (4) pair scalars
    const float* xi_noise = b.z[initial ? 2 : 0].data();
    if (noise) {
      pair_noise_numbers(model_.seed, key, i, bj, m, model_.noise, b.z[0].data(), b.z[1].data(),
                         b.z[2].data(), b.z[3].data());
    } else if (!flux_only) {
      std::fill_n(b.z[0].data(), m, 0.0f);
      xi_noise = b.z[0].data();
    }
    tdpd::pair_scalars<D>(pc, m, flux_only, xi_noise, b);
    double* wdc = b.wdc.data();
    if (buffers) {  // no flux across the inflow / outflow seam
      for (std::size_t p = 0; p < m; ++p) {
        if (buffers_.across_seam(xi, &xp[3 * bj[p]])) wdc[p] = 0.0;
      }
    }
    // (5) scatter: i sums in block order, j gets the exact negatives
    double fi[D] = {};
    double rho_i = 0.0;
    const double* ci = &cpp[i * nt];
    double* qi = &qpp[i * nt];
    const double* oki = okpp ? &okpp[i * nt] : nullptr;
    for (std::size_t p = 0; p < m; ++p) {
      const std::uint32_t j = bj[p];
      if (!flux_only) {
        const double s = b.s[p];
        for (int k = 0; k < D; ++k) {
          const double fk = s * bd[k][p];
          fi[k] += fk;
          fp[3 * j + k] -= fk;
        }
        rho_i += b.w[p];
        rhop[j] += b.w[p];
      }
      const double w = wdc[p];
      if (w == 0.0) continue;
      const double* cj = &cpp[j * nt];
      double* qj = &qpp[j * nt];
      if (oki) {
        const double* okj = &okpp[j * nt];
        for (std::size_t t = 0; t < nt; ++t) {
          const double dc = w * (cj[t] - ci[t]);
          qi[t] += okj[t] * dc;
          qj[t] -= oki[t] * dc;
        }
      } else {
        for (std::size_t t = 0; t < nt; ++t) {
          const double dc = w * (cj[t] - ci[t]);
          qi[t] += dc;
          qj[t] -= dc;
        }
      }
    }
    if (!flux_only) {
      for (int k = 0; k < D; ++k) fp[3 * i + k] += fi[k];
      rhop[i] += rho_i;
    }
  });

  // Unpack: forces with gravity, fluxes times kappa; frozen wall particles feel no force and
  // get no flux (their species stay fixed: Dirichlet, or unused).
  if (!flux_only) force.resize(3 * n);
  for (auto& q : flux) q.assign(n, 0.0);
  const auto& g = model_.gravity;
#pragma omp parallel for schedule(static) if (ni >= kMinParallelLight)
  for (std::int64_t ii = 0; ii < ni; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    const bool wall = wall_[i] != 0;
    if (!flux_only) {
      for (int k = 0; k < 3; ++k) force[3 * i + k] = wall || k >= D ? 0.0 : fp[3 * i + k] + g[k];
    }
    if (wall) continue;
    for (std::size_t t = 0; t < nt; ++t) {
      const auto sp = static_cast<std::size_t>(transported[t]);
      flux[sp][i] = kappa_[sp] * qpp[i * nt + t];
    }
    if (species_.has_reactions()) species_.add_reactions(i, c, flux);
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
