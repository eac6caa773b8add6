// SPDX-License-Identifier: MIT
/// \file tdpd_pair_block.cpp
/// tdpd::pair_scalars: the SIMD part of the tDPD pair loop (see tdpd_pair_block.hpp).
#include "tdpd_pair_block.hpp"

#include <cmath>

namespace sadr::fluid::tdpd {
namespace {

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && \
    !defined(__SANITIZE_ADDRESS__)
// This file is compiled with -ffp-contract=off and -fno-math-errno: the clones give the same
// bits (no FMA contraction), and sqrt vectorises.
#define SADR_TDPD_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define SADR_TDPD_CLONES
#endif

/// How w_R = w_C^(s1/2) is computed: exact shortcuts for s1 = 0, 1, 2, else pow_unit.
enum class WeightForm { kOne, kSqrt, kLinear, kPow };

template <int D, WeightForm W>
SADR_TDPD_CLONES void scalars_impl(const PairConsts& c, std::size_t m, const float* __restrict xi,
                                   PairBlock& b) {
  const double* __restrict d0 = b.d[0].data();
  const double* __restrict d1 = b.d[1].data();
  const double* __restrict d2 = b.d[2].data();
  const double* __restrict v0 = b.dv[0].data();
  const double* __restrict v1 = b.dv[1].data();
  const double* __restrict v2 = b.dv[2].data();
  const double* __restrict r2p = b.r2.data();
  double* __restrict sp = b.s.data();
  double* __restrict wp = b.w.data();
  double* __restrict wdcp = b.wdc.data();
  const double inv_rc = c.inv_rc, rcc2 = c.rcc2, inv_rcc = c.inv_rcc, a = c.a, gamma = c.gamma,
               half_s1 = c.half_s1, sigma_dt = c.sigma_dt, alpha = c.kernel_w0;
  // (GCC 12 does not trust __restrict on these locals and gives up on the alias checks)
#pragma GCC ivdep
  for (std::size_t k = 0; k < m; ++k) {
    const double r2 = r2p[k];
    const double r = std::sqrt(r2);
    const double inv_r = 1.0 / r;
    const double q = r * inv_rc;
    const double wc = 1.0 - q;
    const double sc = 1.0 - r * inv_rcc;
    wdcp[k] = r2 < rcc2 ? sc * sc : 0.0;
    wp[k] = alpha * (1.0 + 3.0 * q) * wc * wc * wc;  // Lucy W (Kernel::w), q < 1 here
    double wr = 1.0;
    if constexpr (W == WeightForm::kSqrt) wr = std::sqrt(wc);
    if constexpr (W == WeightForm::kLinear) wr = wc;
    if constexpr (W == WeightForm::kPow) wr = pow_unit(wc, half_s1);
    double ev = d0[k] * v0[k];
    if constexpr (D > 1) ev += d1[k] * v1[k];
    if constexpr (D > 2) ev += d2[k] * v2[k];
    ev *= inv_r;
    const double fmag = a * wc - gamma * wr * wr * ev + sigma_dt * wr * static_cast<double>(xi[k]);
    sp[k] = fmag * inv_r;
  }
}

SADR_TDPD_CLONES void flux_only_impl(const PairConsts& c, std::size_t m, PairBlock& b) {
  const double* __restrict r2p = b.r2.data();
  double* __restrict wdcp = b.wdc.data();
  const double rcc2 = c.rcc2, inv_rcc = c.inv_rcc;
#pragma GCC ivdep
  for (std::size_t k = 0; k < m; ++k) {
    const double sc = 1.0 - std::sqrt(r2p[k]) * inv_rcc;
    wdcp[k] = r2p[k] < rcc2 ? sc * sc : 0.0;
  }
}

}  // namespace

template <int D>
void pair_scalars(const PairConsts& c, std::size_t m, bool flux_only, const float* xi,
                  PairBlock& b) {
  if (flux_only) {
    flux_only_impl(c, m, b);
    return;
  }
  const double p = c.half_s1;
  if (p == 0.0) {
    scalars_impl<D, WeightForm::kOne>(c, m, xi, b);
  } else if (p == 0.5) {
    scalars_impl<D, WeightForm::kSqrt>(c, m, xi, b);
  } else if (p == 1.0) {
    scalars_impl<D, WeightForm::kLinear>(c, m, xi, b);
  } else {
    scalars_impl<D, WeightForm::kPow>(c, m, xi, b);
  }
}

template void pair_scalars<1>(const PairConsts&, std::size_t, bool, const float*, PairBlock&);
template void pair_scalars<2>(const PairConsts&, std::size_t, bool, const float*, PairBlock&);
template void pair_scalars<3>(const PairConsts&, std::size_t, bool, const float*, PairBlock&);

}  // namespace sadr::fluid::tdpd
