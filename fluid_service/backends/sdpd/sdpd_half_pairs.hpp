// SPDX-License-Identifier: MIT
/// \file sdpd_half_pairs.hpp
/// SdpdBackend::evaluate_half (included by sdpd_rates.cpp only): the pair loop for systems
/// without wall particles, Morris walls, transported species or reactions, evaluating every
/// pair ONCE (the full-list gather evaluates it from both sides) and writing +F to i and -F
/// to j, including the thermal-noise numbers (generated once per pair instead of twice).
///
/// Determinism without atomics: particles are binned into slabs of width >= list cutoff / R
/// (R = kSlabReach = 2) along the last active axis at each list build (rebuild_neighbors), so
/// a listed pair spans at most R + 1 consecutive slabs. The list is filtered to "forward" pairs:
/// j in the same slab with j > i, or j 1..R slabs ahead (mod the slab count on a periodic axis,
/// a multiple of R + 1 above 2R). Phase p runs the slabs s = p mod (R + 1) in parallel; slab s
/// writes only to slabs s..s+R, so no two threads write the same particle, and each particle
/// receives its contributions in an order fixed by (phase, slab, member index): independent
/// of the thread count. The slab assignment depends on the positions at the last list build,
/// which are saved with the state (blob version 2), so restarts stay bit-exact. The pair values are
/// those of the compact block (sdpd_pair_block.hpp); the j side uses the exact negatives (forces,
/// noise) and its own continuity / viscous-limit terms, so momentum is conserved to round-off.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>

#include "sadr/common/status.hpp"

#include "sadr/fluid/pair_noise_batch.hpp"
#include "sadr/fluid/parallel.hpp"
#include "sdpd_backend.hpp"

namespace sadr::fluid {

// Defined here (one translation unit: sdpd_rates.cpp) next to the loops that use the slabs.
void SdpdBackend::rebuild_neighbors(const std::vector<double>& x) {
  builder_->build(x, nlist_);
  list_ref_x_ = x;
  if (!half_ok_) return;
  // Slabs along the last active axis of width >= cutoff/kSlabReach, so a listed pair spans at
  // most kSlabReach + 1 consecutive slabs; on a periodic axis a multiple of kSlabReach + 1 slabs
  // (the colours) and more than 2 kSlabReach (else one slab: serial, still exact).
  // kSlabReach = 2 rather than 1: 3D, 1e4 particles gives 12 slabs (4 per colour) instead of 6
  // (3 per colour, which caps 2 threads at 1.5x).
  const int axis = model_.box.dimension - 1;
  const double len = pbox_.length(axis);
  // (1 + 1e-9): a listed pair stays within kSlabReach slabs despite rounding in the binning
  auto ns = static_cast<std::uint32_t>(
      std::floor(kSlabReach * len / (builder_->cutoff() * (1.0 + 1e-9))));
  slab_wrap_ = pbox_.periodic(axis);
  if (slab_wrap_) {
    ns -= ns % (kSlabReach + 1);
    if (ns <= 2 * kSlabReach) ns = 1;
  }
  slab_count_ = std::max<std::uint32_t>(ns, 1);
  const double lo = model_.box.lo[axis], inv_w = slab_count_ / len;
  const std::size_t n = x.size() / 3;
  slab_of_.resize(n);
  slab_start_.assign(slab_count_ + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = std::floor((x[3 * i + axis] - lo) * inv_w);
    const auto s = static_cast<std::uint32_t>(std::clamp(t, 0.0, slab_count_ - 1.0));
    slab_of_[i] = s;
    ++slab_start_[s + 1];
  }
  for (std::uint32_t s = 0; s < slab_count_; ++s) slab_start_[s + 1] += slab_start_[s];
  slab_members_.resize(n);
  std::vector<std::uint32_t> fill(slab_start_.begin(), slab_start_.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
    slab_members_[fill[slab_of_[i]]++] = static_cast<std::uint32_t>(i);
  // Keep only the "forward" pairs (sdpd_half_pairs.hpp), in place: every pair is listed once,
  // which halves the list memory (and the pair loops need no slab test per entry).
  std::uint32_t out = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t s = slab_of_[i];
    const std::uint32_t begin = nlist_.offsets[i], end = nlist_.offsets[i + 1];
    nlist_.offsets[i] = out;
    for (std::uint32_t k = begin; k < end; ++k) {
      const std::uint32_t j = nlist_.indices[k];
      // slab distance forward (mod the count on a periodic axis; "negative" is huge unsigned)
      std::uint32_t ds = slab_of_[j] - s;
      if (slab_wrap_ && slab_of_[j] < s) ds += slab_count_;
      if (ds == 0 ? j > i : ds <= kSlabReach) nlist_.indices[out++] = j;
    }
  }
  // The full list is symmetric, so exactly half of it must remain (no pair lost or doubled).
  if (2 * static_cast<std::size_t>(out) != nlist_.indices.size()) {
    throw NumericalFailure("sdpd: slab filter kept " + std::to_string(out) + " of " +
                               std::to_string(nlist_.indices.size()) + " list entries (internal)",
                           {{"quantity", "neighbour list"}});
  }
  nlist_.offsets[n] = out;
  nlist_.indices.resize(out);
  nlist_.indices.shrink_to_fit();
}

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && \
    !defined(__SANITIZE_ADDRESS__)
// AVX2 has no FMA, so the clone cannot contract mul + add (results equal the default clone's).
#define SADR_SIDE_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define SADR_SIDE_CLONES
#endif

struct HalfSideI {
  double m_i, vol_i, rho_i, two_dhc0, eps;
};

/// Vectorisable per-pair values of the half path (k < m): side[0..D) the noise impulse on i,
/// amp z_a + (amp_r z3) x_a (PairNoise::add); side[3] the j side of the continuity term,
/// -m_i F (x.v) + 2 delta h c0 V_i (rho_i - rho_j) F r^2/(r^2 + eps h^2) (x_ji.v_ji = x_ij.v_ij).
template <int D>
SADR_SIDE_CLONES void half_side_terms(const SdpdPairBlock& b,
                                      const std::array<std::vector<float>, 4>& z, std::size_t m,
                                      bool continuity, bool noise, HalfSideI p,
                                      std::array<std::vector<double>, 4>& side) {
  if (continuity) {
    double* __restrict dj = side[3].data();
    const double* __restrict f = b.f.data();
    const double* __restrict r2 = b.r2.data();
    const double* __restrict rhoj = b.rho_j.data();
    const double* __restrict x0 = b.x[0].data();
    const double* __restrict x1 = b.x[1].data();
    const double* __restrict x2 = b.x[2].data();
    const double* __restrict v0 = b.v[0].data();
    const double* __restrict v1 = b.v[1].data();
    const double* __restrict v2 = b.v[2].data();
    for (std::size_t k = 0; k < m; ++k) {
      double xv = x0[k] * v0[k];
      if constexpr (D > 1) xv += x1[k] * v1[k];
      if constexpr (D > 2) xv += x2[k] * v2[k];
      dj[k] = -p.m_i * f[k] * xv +
              p.two_dhc0 * p.vol_i * (p.rho_i - rhoj[k]) * f[k] * r2[k] / (r2[k] + p.eps);
    }
  }
  if (noise) {
    const double* __restrict amp = b.amp.data();
    const double* __restrict amp_r = b.amp_r.data();
    const float* __restrict z3 = z[3].data();
    for (int a = 0; a < D; ++a) {
      double* __restrict out = side[a].data();
      const double* __restrict xa = b.x[a].data();
      const float* __restrict za = z[a].data();
      for (std::size_t k = 0; k < m; ++k) {
        const double s3 = amp_r[k] * static_cast<double>(z3[k]);
        out[k] = amp[k] * static_cast<double>(za[k]) + s3 * xa[k];
      }
    }
  }
}

template <class PerParticle>
void SdpdBackend::slab_phases(PerParticle&& per_particle) {
  [[maybe_unused]] const auto ni = static_cast<std::int64_t>(mass_.size());
  constexpr std::uint32_t colours = kSlabReach + 1;
  // (the summation-density pass runs before evaluate_dim sizes the scratch; UBSan found it)
  if (scratch_.size() < static_cast<std::size_t>(max_threads()))
    scratch_.resize(static_cast<std::size_t>(max_threads()));
    // One parallel region for the three colours (the implicit barrier of each `omp for` orders
    // them): fewer thread wake-ups on a loaded machine than one region per colour.
#pragma omp parallel if (ni > kMinParallel)
  {
    PairScratch& sc = scratch_[static_cast<std::size_t>(thread_index())];
    for (std::uint32_t phase = 0; phase < colours; ++phase) {
      const auto tasks = static_cast<std::int64_t>((slab_count_ + colours - 1 - phase) / colours);
#pragma omp for schedule(dynamic, 1)
      for (std::int64_t t = 0; t < tasks; ++t) {
        const auto s = static_cast<std::size_t>(phase + colours * t);
        for (std::uint32_t k = slab_start_[s]; k < slab_start_[s + 1]; ++k)
          per_particle(slab_members_[k], sc);
      }
    }
  }
}

template <int D>
void SdpdBackend::summation_half(Y& y) {
  // SPEC eq 19, rho_i = m_i W(0) + sum_j m_j W_ij, with each pair evaluated once (no walls here)
  const std::size_t n = mass_.size();
  const double h2 = kernel_.support() * kernel_.support();
  for (std::size_t i = 0; i < n; ++i) y.rho[i] = mass_[i] * kernel_.w0();
  const double* x = y.x.data();
  double* rho = y.rho.data();
  slab_phases([&](std::uint32_t i, PairScratch&) {
    const double* xi = &x[3 * i];
    double sum = 0;
    for (const std::uint32_t j : nlist_.of(i)) {
      double d[D];
      for (int a = 0; a < D; ++a) d[a] = xi[a] - x[3 * j + a];
      pbox_.minimum_image_first<D>(d);
      double r2 = 0;
      for (int a = 0; a < D; ++a) r2 += d[a] * d[a];
      if (r2 >= h2) continue;
      const double w = kernel_.w(std::sqrt(r2));
      sum += mass_[j] * w;
      rho[j] += mass_[i] * w;
    }
    rho[i] += sum;
  });
}

template <int D>
void SdpdBackend::evaluate_half(const Y& y, std::uint64_t noise_step, Rates& out, bool noise_on,
                                const SdpdPairParams& pp, double c_d) {
  const std::size_t n = mass_.size();
  const auto ni = static_cast<std::int64_t>(n);
  const double h = kernel_.support();
  const double h2 = h * h;
  const bool continuity = model_.density_mode != DensityMode::kSummation;
  const double* x = y.x.data();
  const double* v = y.v.data();
  double* acc = out.acc.data();  // force sums first, accelerations at the end
  double* accn = noise_on ? out.acc_noise.data() : nullptr;
  double* drho = out.drho.data();
  fsum_.assign(n, 0.0);
  double* fsum = fsum_.data();
  const double two_dhc0 = 2.0 * pp.delta_h_c0, eps = pp.eps_h2;
  slab_phases([&](std::uint32_t i, PairScratch& sc) {
    SdpdPairBlock& b = sc.block;
    const auto list = nlist_.of(i);
    sc.reserve(list.size());
    const double* xi = &x[3 * i];
    const double* vi = &v[3 * i];
    // Two passes (callgrind, 3D 1e4: -6.5% instructions against one pass): (1) minimum image
    // and r^2 for every forward entry, compacted branch-free (each entry written at slot m,
    // m advances if r < h: the cut-off branch is unpredictable, ~1/3 of the entries lie in
    // the skin); (2) the per-particle data of the m pairs within h only. Block pointers are
    // hoisted (GCC reloads them from the vectors otherwise).
    std::uint32_t* __restrict bj = b.j.data();
    double* __restrict bx[3] = {b.x[0].data(), b.x[1].data(), b.x[2].data()};
    double* __restrict bv[3] = {b.v[0].data(), b.v[1].data(), b.v[2].data()};
    double* __restrict br2 = b.r2.data();
    double* __restrict bpd2 = b.pd2_j.data();
    double* __restrict bind = b.inv_nd_j.data();
    double* __restrict bm = b.m_j.data();
    double* __restrict bvol = b.vol_j.data();
    double* __restrict brho = b.rho_j.data();
    double* __restrict bsq = b.sqrt_inv_nd_j.data();
    const double* __restrict sq = noise_on ? sqrt_inv_nd_.data() : vol_.data();
    std::size_t m = 0;
    for (const std::uint32_t j : list) {  // forward pairs only (rebuild_neighbors)
      double d[D];
      for (int a = 0; a < D; ++a) d[a] = xi[a] - x[3 * j + a];
      pbox_.minimum_image_first<D>(d);
      double r2 = 0;
      for (int a = 0; a < D; ++a) r2 += d[a] * d[a];
      bj[m] = j;
      for (int a = 0; a < D; ++a) bx[a][m] = d[a];
      br2[m] = r2;
      m += r2 < h2 ? 1 : 0;
    }
    // second pass over the m pairs within h only (~2/3 of the entries): per-particle data
    for (std::size_t k = 0; k < m; ++k) {
      const std::uint32_t j = bj[k];
      for (int a = 0; a < D; ++a) bv[a][k] = vi[a] - v[3 * j + a];
      bpd2[k] = pd2_[j];
      bind[k] = inv_nd_[j];
      bm[k] = mass_[j];
      bvol[k] = vol_[j];
      brho[k] = y.rho[j];
      bsq[k] = sq[j];
    }
    if (m == 0) return;
    const double rho_i = y.rho[i], m_i = mass_[i], vol_i = vol_[i], ind_i = inv_nd_[i];
    sdpd_pair_block<D>(pp, {i, pd2_[i], ind_i, rho_i, noise_on ? sqrt_inv_nd_[i] : 0.0}, m, b);
    if (noise_on) {
      // core's clones: avx512f (16 lanes) / avx2 / default, the same bits on each
      pair_noise_numbers(model_.seed, noise_step, i, b.j.data(), m, model_.noise, sc.z[0].data(),
                         sc.z[1].data(), sc.z[2].data(), sc.z[3].data());
    }
    half_side_terms<D>(b, sc.z, m, continuity, noise_on, {m_i, vol_i, rho_i, two_dhc0, eps},
                       sc.side);
    // One scatter pass: i sums in list order, j gets the exact negatives (and its own terms).
    const double* dj = sc.side[3].data();
    double force[D] = {}, fn[D] = {}, dr = 0, fs = 0;
    for (std::size_t k = 0; k < m; ++k) {
      const std::uint32_t j = b.j[k];
      const double f = b.f[k];
      for (int a = 0; a < D; ++a) {
        force[a] += b.force[a][k];
        acc[3 * j + a] -= b.force[a][k];
      }
      fs += f * b.inv_nd_j[k];
      fsum[j] += f * ind_i;
      if (continuity) {
        dr += b.drho[k];
        drho[j] += dj[k];
      }
      if (noise_on) {
        for (int a = 0; a < D; ++a) {
          fn[a] += sc.side[a][k];
          accn[3 * j + a] -= sc.side[a][k];
        }
      }
    }
    for (int a = 0; a < D; ++a) acc[3 * i + a] += force[a];
    fsum[i] += fs;
    if (continuity) drho[i] += dr;
    if (noise_on) {
      for (int a = 0; a < D; ++a) accn[3 * i + a] += fn[a];
    }
  });
  double max_visc = 0;
  const auto& bq = model_.boussinesq;
#pragma omp parallel for schedule(static) if (ni > kMinParallel) reduction(max : max_visc)
  for (std::int64_t ii = 0; ii < ni; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    max_visc = std::max(max_visc, fsum[i] / y.rho[i]);
    const double inv_m = 1.0 / mass_[i];
    double body[3] = {model_.gravity[0], model_.gravity[1], model_.gravity[2]};
    if (bq.species >= 0) {
      const double bqa = bq.coefficient * (y.c[bq.species][i] - bq.reference);
      for (int a = 0; a < 3; ++a) body[a] += bqa * bq.direction[a];
    }
    for (int a = 0; a < D; ++a) acc[3 * i + a] = acc[3 * i + a] * inv_m + body[a];
    if (noise_on) {
      for (int a = 0; a < D; ++a) accn[3 * i + a] *= inv_m;
    }
  }
  out.max_k_sum = 0;
  out.max_visc_sum = 2.0 * c_d * max_visc;
}

}  // namespace sadr::fluid
