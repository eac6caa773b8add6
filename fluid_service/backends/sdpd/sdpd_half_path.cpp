// SPDX-License-Identifier: MIT
/// \file sdpd_half_path.cpp
/// The SDPD pair loop for systems without wall particles, Morris walls, transported species or
/// reactions: every pair is evaluated ONCE (the full-list gather evaluates it from both sides)
/// and writes +F to i and -F to j, including the thermal-noise numbers (generated once per pair
/// instead of twice). The slabs and their order are the core SlabScheduler's
/// (slab_scheduler.hpp): no atomics, results independent of the thread count. The slab
/// assignment depends on the positions at the last list build, which are saved with the state
/// (blob version 2), so restarts stay bit-exact. The pair values are those of the compact block
/// (sdpd_pair_block.hpp); the j side uses the exact negatives (forces, noise) and its own
/// continuity / viscous-limit terms, so momentum is conserved to round-off.
///
/// Memory layout (measured: 2D 1e5 +35-45% per core, 3D +5-15%, bit-identical): what a pair
/// reads of j (HalfIn) and adds to j (HalfAcc) are one 64-byte line each; in 2D a few particles
/// of a slab share one block (per-lane i quantities) so the noise vectors are full. Neither
/// changes an operation or the order of the sums.
#include <algorithm>
#include <cmath>

#include "sadr/fluid/pair_noise_batch.hpp"
#include "sadr/fluid/parallel.hpp"
#include "sdpd_backend.hpp"

namespace sadr::fluid {

// (external linkage, as the core's noise clones: target_clones needs an ifunc symbol)
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && \
    !defined(__SANITIZE_ADDRESS__)
// AVX2 has no FMA, so the clone cannot contract mul + add (results equal the default clone's).
#define SADR_SIDE_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define SADR_SIDE_CLONES
#endif

struct HalfSideParams {
  double two_dhc0, eps;
  double m_i = 0, vol_i = 0, rho_i = 0;  ///< one particle per block (!kLanes)
};

/// Vectorisable per-pair values of the half path (k < m; with kLanes the i quantities per lane,
/// as in sdpd_pair_block_lanes, else those of `p`): side[0..D) the noise impulse on i, amp z_a +
/// (amp_r z3) x_a (PairNoise::add); side[3] the j side of the continuity term, -m_i F (x.v) + 2
/// delta h c0 V_i (rho_i - rho_j) F r^2/(r^2 + eps h^2) (x_ji.v_ji = x_ij.v_ij; V_i = m_i/rho_i is
/// bitwise 1/d_i = b.inv_nd_i).
template <int D, bool kLanes>
SADR_SIDE_CLONES void half_side_terms(const SdpdPairBlock& b,
                                      const std::array<std::vector<float>, 4>& z,
                                      const std::vector<double>& m_i, std::size_t m,
                                      bool continuity, bool noise, HalfSideParams p,
                                      std::array<std::vector<double>, 4>& side) {
  if (continuity) {
    double* __restrict dj = side[3].data();
    const double* __restrict f = b.f.data();
    const double* __restrict r2 = b.r2.data();
    const double* __restrict rhoj = b.rho_j.data();
    const double* __restrict mi = m_i.data();
    const double* __restrict voli = b.inv_nd_i.data();
    const double* __restrict rhoi = b.rho_i.data();
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
      const double m_i_k = kLanes ? mi[k] : p.m_i;
      const double vol_i_k = kLanes ? voli[k] : p.vol_i;
      const double rho_i_k = kLanes ? rhoi[k] : p.rho_i;
      // i <-> j of the i side: rho_i_k is "rho_j" here and rhoj[k] "rho_i"
      dj[k] =
          sdpd::density_rate(m_i_k, f[k], xv, p.two_dhc0, vol_i_k, rhoj[k], rho_i_k, r2[k], p.eps);
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

template <int D>
void SdpdBackend::summation_half(Y& y) {
  // Summation density (docs/method.md), rho_i = m_i W(0) + sum_j m_j W_ij, with each pair
  // evaluated once (no walls here)
  const std::size_t n = mass_.size();
  const double h2 = kernel_.support() * kernel_.support();
  for (std::size_t i = 0; i < n; ++i) y.rho[i] = mass_[i] * kernel_.w0();
  const double* x = y.x.data();
  double* rho = y.rho.data();
  ensure_scratch();
  slabs_.run(
      [&](const std::uint32_t* first, const std::uint32_t* last, std::size_t) {
        for (; first != last; ++first) {
          const std::uint32_t i = *first;
          const double* xi = &x[3 * i];
          double sum = 0;
          for (const std::uint32_t j : nlist_.of(i)) {
            double d[D];
            const double r2 = pbox_.offset_first<D>(xi, &x[3 * j], d);
            if (r2 >= h2) continue;
            const double w = kernel_.w(std::sqrt(r2));
            sum += mass_[j] * w;
            rho[j] += mass_[i] * w;
          }
          rho[i] += sum;
        }
      },
      static_cast<std::int64_t>(n) > kMinParallel);
}

template <int D>
void SdpdBackend::half_pairs_team(const Y& y, std::uint64_t noise_step, bool noise_on,
                                  const SdpdPairParams& pp, SlabMembersFn after) {
  const double h = kernel_.support();
  const double h2 = h * h;
  const bool continuity = model_.density_mode != DensityMode::kSummation;
  const double* x = y.x.data();
  const HalfIn* __restrict hin = hin_.data();  // filled by evaluate_half / fused_substep
  HalfAcc* __restrict hacc = hacc_.data();     // zeroed there too
  // A few consecutive members of a slab share one block: 2D has ~12 pairs per particle, so one
  // particle per block leaves the 16-lane noise vectors a quarter empty and pays the call
  // overheads per 12 pairs. Every pair gives the same bits as alone, and the scatter below
  // keeps the particle order, so the result is bit-identical to one particle per block.
  constexpr std::size_t kGroupEntries = 64;  // list entries per block (3D: one particle)
  auto per_slab = [&](const std::uint32_t* first, const std::uint32_t* last, std::size_t t) {
    PairScratch& sc = scratch_[t];
    while (first != last) {
      const std::uint32_t* group_end = first;
      std::size_t entries = 0;
      while (group_end != last && entries < kGroupEntries)
        entries += nlist_.of(*group_end++).size();
      sc.reserve(entries);
      sc.seg_end.resize(static_cast<std::size_t>(group_end - first));
      SdpdPairBlock& b = sc.block;
      // 3D (~46 pairs per particle): one particle per block, i quantities broadcast (the
      // per-lane copies cost more than the fuller vectors gain there)
      const bool lanes = group_end - first > 1;
      // Per particle, two passes (callgrind, 3D 1e4: -6.5% instructions against one pass):
      // (1) minimum image and r^2 for every forward entry, compacted branch-free (each entry
      // written at slot m, m advances if r < h: the cut-off branch is unpredictable, ~1/3 of
      // the entries lie in the skin); (2) the per-particle data of the pairs within h only.
      // Block pointers are hoisted (GCC reloads them from the vectors otherwise).
      std::uint32_t* __restrict bj = b.j.data();
      std::uint32_t* __restrict bi = b.i.data();
      double* __restrict bx[3] = {b.x[0].data(), b.x[1].data(), b.x[2].data()};
      double* __restrict bv[3] = {b.v[0].data(), b.v[1].data(), b.v[2].data()};
      double* __restrict br2 = b.r2.data();
      double* __restrict bpd2 = b.pd2_j.data();
      double* __restrict bind = b.inv_nd_j.data();
      double* __restrict bm = b.m_j.data();
      double* __restrict bvol = b.vol_j.data();
      double* __restrict brho = b.rho_j.data();
      double* __restrict bsq = b.sqrt_inv_nd_j.data();
      double* __restrict bpd2i = b.pd2_i.data();
      double* __restrict bindi = b.inv_nd_i.data();
      double* __restrict brhoi = b.rho_i.data();
      double* __restrict bsqi = b.sqrt_inv_nd_i.data();
      double* __restrict bmi = sc.m_i.data();
      std::size_t m = 0;
      for (const std::uint32_t* p = first; p != group_end; ++p) {
        const std::uint32_t i = *p;
        const std::size_t m0 = m;
        const double* xi = &x[3 * i];
        for (const std::uint32_t j : nlist_.of(i)) {  // forward pairs only (rebuild_neighbors)
          double d[D];
          const double r2 = pbox_.offset_first<D>(xi, &x[3 * j], d);
          bj[m] = j;
          for (int a = 0; a < D; ++a) bx[a][m] = d[a];
          br2[m] = r2;
          m += r2 < h2 ? 1 : 0;
        }
        const HalfIn& pi = hin[i];
        for (std::size_t k = m0; k < m; ++k) {
          const HalfIn& pj = hin[bj[k]];
          for (int a = 0; a < D; ++a) bv[a][k] = pi.v[a] - pj.v[a];
          bpd2[k] = pj.pd2;
          bind[k] = pj.inv_nd;
          bm[k] = pj.m;
          bvol[k] = pj.inv_nd;  // V_j = m_j/rho_j, bitwise 1/d_j
          brho[k] = pj.rho;
          bsq[k] = pj.sqrt_inv_nd;
        }
        for (std::size_t k = m0; k < m && lanes; ++k) {
          bi[k] = i;
          bpd2i[k] = pi.pd2;
          bindi[k] = pi.inv_nd;
          brhoi[k] = pi.rho;
          bsqi[k] = pi.sqrt_inv_nd;
          bmi[k] = pi.m;
        }
        sc.seg_end[static_cast<std::size_t>(p - first)] = static_cast<std::uint32_t>(m);
      }
      float* z[4] = {sc.z[0].data(), sc.z[1].data(), sc.z[2].data(), sc.z[3].data()};
      // core's noise clones: avx512f (16 lanes) / avx2 / default, the same bits on each
      HalfSideParams sp{2.0 * pp.delta_h_c0, pp.eps_h2};
      if (m > 0 && lanes) {
        sdpd_pair_block_lanes<D>(pp, m, b);
        if (noise_on) {
          pair_noise_numbers_lanes(model_.seed, noise_step, b.i.data(), b.j.data(), m, model_.noise,
                                   z[0], z[1], z[2], z[3]);
        }
        half_side_terms<D, true>(b, sc.z, sc.m_i, m, continuity, noise_on, sp, sc.side);
      } else if (m > 0) {
        const HalfIn& pi = hin[*first];
        sdpd_pair_block<D>(pp, {*first, pi.pd2, pi.inv_nd, pi.rho, pi.sqrt_inv_nd}, m, b);
        if (noise_on) {
          pair_noise_numbers(model_.seed, noise_step, *first, b.j.data(), m, model_.noise, z[0],
                             z[1], z[2], z[3]);
        }
        sp.m_i = pi.m;
        sp.vol_i = pi.inv_nd;
        sp.rho_i = pi.rho;
        half_side_terms<D, false>(b, sc.z, sc.m_i, m, continuity, noise_on, sp, sc.side);
      }
      // Scatter particle by particle (member order): i sums its pairs in list order, j gets the
      // exact negatives (and its own terms).
      const double* dj = sc.side[3].data();
      std::size_t k = 0;
      for (const std::uint32_t* p = first; p != group_end; ++p) {
        const std::uint32_t i = *p;
        const std::size_t end = sc.seg_end[static_cast<std::size_t>(p - first)];
        if (k == end) continue;  // no pair within h: i is left untouched
        const double ind_i = hin[i].inv_nd;
        double force[D] = {}, fn[D] = {}, dr = 0, fs = 0;
        for (; k < end; ++k) {
          HalfAcc& aj = hacc[b.j[k]];
          const double f = b.f[k];
          for (int a = 0; a < D; ++a) {
            force[a] += b.force[a][k];
            aj.force[a] -= b.force[a][k];
          }
          fs += f * b.inv_nd_j[k];
          aj.fsum += f * ind_i;
          if (continuity) {
            dr += b.drho[k];
            aj.drho += dj[k];
          }
          if (noise_on) {
            for (int a = 0; a < D; ++a) {
              fn[a] += sc.side[a][k];
              aj.noise[a] -= sc.side[a][k];
            }
          }
        }
        HalfAcc& ai = hacc[i];
        for (int a = 0; a < D; ++a) ai.force[a] += force[a];
        ai.fsum += fs;
        if (continuity) ai.drho += dr;
        if (noise_on) {
          for (int a = 0; a < D; ++a) ai.noise[a] += fn[a];
        }
      }
      first = group_end;
    }
  };
  slabs_.run_team(per_slab, after);
}

template <int D>
void SdpdBackend::evaluate_half(Y& y, std::uint64_t noise_step, Rates& out, bool noise_on) {
  const std::size_t n = mass_.size();
  const auto ni = static_cast<std::int64_t>(n);
  // (every entry of acc, acc_noise and drho is written at the end)
  out.acc.resize(3 * n);
  out.acc_noise.resize(noise_on ? 3 * n : 0);
  out.drho.resize(n);
  out.dc.resize(y.c.size());
  for (auto& d : out.dc) d.assign(n, 0.0);
  if (model_.density_mode == DensityMode::kSummation) summation_half<D>(y);
  hin_.resize(n);
  hacc_.resize(n);
#pragma omp parallel for schedule(static) if (ni > kMinParallelLight)
  for (std::int64_t ii = 0; ii < ni; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    fill_half_in(i, y, noise_on);
    hacc_[i] = HalfAcc{};
  }
  const SdpdPairParams pp = make_pair_params<D>(noise_on);
  const double c_d = sdpd::viscosity_factor<D>();
  ensure_scratch();
  slabs_.next_pass();
#pragma omp parallel if (ni > kMinParallel)
  half_pairs_team<D>(y, noise_step, noise_on, pp, {});
  double max_visc = 0;
  double* acc = out.acc.data();
  double* accn = noise_on ? out.acc_noise.data() : nullptr;
  double* drho = out.drho.data();
#pragma omp parallel for schedule(static) if (ni > kMinParallelLight) reduction(max : max_visc)
  for (std::int64_t ii = 0; ii < ni; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    half_rates<D>(i, y, noise_on, &acc[3 * i], noise_on ? &accn[3 * i] : nullptr, &drho[i],
                  max_visc);
  }
  out.max_k_sum = 0;
  out.max_visc_sum = 2.0 * c_d * max_visc;
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

template void SdpdBackend::evaluate_half<1>(Y&, std::uint64_t, Rates&, bool);
template void SdpdBackend::evaluate_half<2>(Y&, std::uint64_t, Rates&, bool);
template void SdpdBackend::evaluate_half<3>(Y&, std::uint64_t, Rates&, bool);
template void SdpdBackend::half_pairs_team<1>(const Y&, std::uint64_t, bool, const SdpdPairParams&,
                                              SlabMembersFn);
template void SdpdBackend::half_pairs_team<2>(const Y&, std::uint64_t, bool, const SdpdPairParams&,
                                              SlabMembersFn);
template void SdpdBackend::half_pairs_team<3>(const Y&, std::uint64_t, bool, const SdpdPairParams&,
                                              SlabMembersFn);

}  // namespace sadr::fluid
