// SPDX-License-Identifier: MIT
#include "sdpd_pair_block.hpp"

#include <cmath>

#include "sdpd_pair_physics.hpp"

namespace sadr::fluid {

void SdpdPairBlock::reserve(std::size_t n) {
  if (j.size() >= n) return;
  j.resize(n);
  i.resize(n);
  for (auto* a : {&x, &v, &force}) {
    for (auto& c : *a) c.resize(n);
  }
  for (auto* a : {&r2, &pd2_j, &inv_nd_j, &m_j, &vol_j, &rho_j, &sqrt_inv_nd_j, &drho, &r, &f, &amp,
                  &amp_r, &pd2_i, &inv_nd_i, &rho_i, &sqrt_inv_nd_i}) {
    a->resize(n);
  }
}

std::size_t SdpdPairBlock::bytes() const {
  return j.capacity() * (4 + 4 + 8 * 3 * 3 + 8 * 16);
}

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && \
    !defined(__SANITIZE_ADDRESS__)
#define SADR_PAIR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define SADR_PAIR_CLONES
#endif

namespace {

// kLanes: the i quantities are read per lane (sdpd_pair_block_lanes) instead of broadcast;
// the arithmetic is the same, so a pair gives the same bits either way.
template <int D, bool kLucy, bool kLanes>
SADR_PAIR_CLONES void block_impl(const SdpdPairParams& p, const SdpdPairI& pi, std::size_t n,
                                 SdpdPairBlock& b) {
  const double* __restrict r2v = b.r2.data();
  const double* __restrict pd2j = b.pd2_j.data();
  const double* __restrict indj = b.inv_nd_j.data();
  const double* __restrict mj = b.m_j.data();
  const double* __restrict volj = b.vol_j.data();
  const double* __restrict rhoj = b.rho_j.data();
  double* __restrict ro = b.r.data();
  double* __restrict fo = b.f.data();
  double* __restrict dro = b.drho.data();
  const double* __restrict x0 = b.x[0].data();
  const double* __restrict x1 = b.x[1].data();
  const double* __restrict x2 = b.x[2].data();
  const double* __restrict v0 = b.v[0].data();
  const double* __restrict v1 = b.v[1].data();
  const double* __restrict v2 = b.v[2].data();
  double* __restrict f0 = b.force[0].data();
  double* __restrict f1 = b.force[1].data();
  double* __restrict f2 = b.force[2].data();
  const double inv_h = p.inv_h, fc = p.f_coef, friction = p.friction;
  const double* __restrict pd2iv = b.pd2_i.data();
  const double* __restrict indiv = b.inv_nd_i.data();
  const double* __restrict rhoiv = b.rho_i.data();
  const double two_dhc0 = 2.0 * p.delta_h_c0, eps = p.eps_h2;
#pragma GCC ivdep
  for (std::size_t k = 0; k < n; ++k) {
    const double pd2_i = kLanes ? pd2iv[k] : pi.pd2;
    const double ind_i = kLanes ? indiv[k] : pi.inv_nd;
    const double rho_i = kLanes ? rhoiv[k] : pi.rho;
    const double r2 = r2v[k];
    const double r = std::sqrt(r2);
    const double inv_r2 = 1.0 / r2;
    const double s = 1.0 - r * inv_h;
    const double f = kLucy ? fc * s * s : fc * s * s * s;
    ro[k] = r;
    fo[k] = f;
    const double fp = sdpd::pressure_factor(pd2_i, pd2j[k], f);
    const double fv = sdpd::viscous_factor(friction, f, ind_i * indj[k]);
    double xv = x0[k] * v0[k];
    if constexpr (D > 1) xv += x1[k] * v1[k];
    if constexpr (D > 2) xv += x2[k] * v2[k];
    const double c = xv * inv_r2;
    f0[k] = sdpd::force_component(fp, fv, x0[k], v0[k], c);
    if constexpr (D > 1) f1[k] = sdpd::force_component(fp, fv, x1[k], v1[k], c);
    if constexpr (D > 2) f2[k] = sdpd::force_component(fp, fv, x2[k], v2[k], c);
    dro[k] = sdpd::density_rate(mj[k], f, xv, two_dhc0, volj[k], rho_i, rhoj[k], r2, eps);
  }
  if (p.noise) {
    const double* __restrict sqj = b.sqrt_inv_nd_j.data();
    const std::uint32_t* __restrict jj = b.j.data();
    double* __restrict amp = b.amp.data();
    double* __restrict amp_r = b.amp_r.data();
    const double* __restrict sqiv = b.sqrt_inv_nd_i.data();
    const std::uint32_t* __restrict iiv = b.i.data();
    const double sfc = p.sqrt_f_coef, na = p.noise_amp;
#pragma GCC ivdep
    for (std::size_t k = 0; k < n; ++k) {
      const double sq_i = kLanes ? sqiv[k] : pi.sqrt_inv_nd;
      const std::uint32_t i = kLanes ? iiv[k] : pi.i;
      const double r = ro[k];
      const double s = 1.0 - r * inv_h;
      const double sf = kLucy ? sfc * s : sfc * s * std::sqrt(s);
      const double a = sdpd::noise_amplitude(na, sf, sq_i, sqj[k]);
      amp[k] = i < jj[k] ? a : -a;
      amp_r[k] = a / r;
    }
  }
}

}  // namespace

template <int D>
void sdpd_pair_block(const SdpdPairParams& p, const SdpdPairI& pi, std::size_t n,
                     SdpdPairBlock& b) {
  if (p.lucy) {
    block_impl<D, true, false>(p, pi, n, b);
  } else {
    block_impl<D, false, false>(p, pi, n, b);
  }
}

template <int D>
void sdpd_pair_block_lanes(const SdpdPairParams& p, std::size_t n, SdpdPairBlock& b) {
  const SdpdPairI unused{0, 0, 0, 0, 0};
  if (p.lucy) {
    block_impl<D, true, true>(p, unused, n, b);
  } else {
    block_impl<D, false, true>(p, unused, n, b);
  }
}

template void sdpd_pair_block<1>(const SdpdPairParams&, const SdpdPairI&, std::size_t,
                                 SdpdPairBlock&);
template void sdpd_pair_block<2>(const SdpdPairParams&, const SdpdPairI&, std::size_t,
                                 SdpdPairBlock&);
template void sdpd_pair_block<3>(const SdpdPairParams&, const SdpdPairI&, std::size_t,
                                 SdpdPairBlock&);
template void sdpd_pair_block_lanes<1>(const SdpdPairParams&, std::size_t, SdpdPairBlock&);
template void sdpd_pair_block_lanes<2>(const SdpdPairParams&, std::size_t, SdpdPairBlock&);
template void sdpd_pair_block_lanes<3>(const SdpdPairParams&, std::size_t, SdpdPairBlock&);

}  // namespace sadr::fluid
