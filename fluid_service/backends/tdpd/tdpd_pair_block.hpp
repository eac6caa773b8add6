// SPDX-License-Identifier: MIT
/// \file tdpd_pair_block.hpp
/// The per-pair arithmetic of the tDPD pair loop on a block of pairs (i, j[k]), k < m, stored
/// structure-of-arrays so that one loop over k runs in SIMD lanes (tdpd_pair_block.cpp, with
/// avx512f / avx2 / default clones; compiled with -ffp-contract=off, so every clone gives the
/// same bits). pow_unit replaces the libm pow call of the weight w_R = w_C^(s1/2).
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <vector>

namespace sadr::fluid::tdpd {

/// x^p for x in {0} or [2^-1022, 1] and p >= 0, as exp(p ln x) with branch-free polynomials
/// (ln: atanh series to t^23 on [sqrt(1/2), sqrt(2)); exp: Cody-Waite reduction and Taylor to
/// degree 13), so that it vectorises. Relative error against std::pow <= 3e-16 (1 + |p ln x|)
/// (unit test), i.e. <= 2.6e-15 for s1 = 0.41 (p ln x >= -7.6); p ln x is clamped at -708
/// (results below 1e-307 are not exact); 0^p = 0 (also for p = 0, where std::pow gives 1).
inline double pow_unit(double x, double p) {
  constexpr double kTwo52 = 4503599627370496.0;
  constexpr double kLn2Hi = 6.93147180369123816490e-01;  // low 32 bits zero: e * hi is exact
  constexpr double kLn2Lo = 1.90821492927058770002e-10;
  const auto bits = std::bit_cast<std::uint64_t>(x);
  // Biased exponent as a double via the 2^52 trick (AVX2/AVX-512F have no int64 -> double).
  double e = std::bit_cast<double>((bits >> 52) | std::bit_cast<std::uint64_t>(kTwo52)) -
             (kTwo52 + 1023.0);
  double m = std::bit_cast<double>((bits & 0x000fffffffffffffULL) | 0x3ff0000000000000ULL);
  const bool big = m > std::numbers::sqrt2;
  m = big ? 0.5 * m : m;
  e = big ? e + 1.0 : e;
  const double t = (m - 1.0) / (m + 1.0);  // |t| <= 0.1716, ln m = 2 atanh t
  const double t2 = t * t;
  double s = 1.0 / 23;
  s = s * t2 + 1.0 / 21;
  s = s * t2 + 1.0 / 19;
  s = s * t2 + 1.0 / 17;
  s = s * t2 + 1.0 / 15;
  s = s * t2 + 1.0 / 13;
  s = s * t2 + 1.0 / 11;
  s = s * t2 + 1.0 / 9;
  s = s * t2 + 1.0 / 7;
  s = s * t2 + 1.0 / 5;
  s = s * t2 + 1.0 / 3;
  const double ln_m = 2.0 * t + 2.0 * t * t2 * s;
  double y = p * (e * kLn2Hi + (ln_m + e * kLn2Lo));
  y = y < -708.0 ? -708.0 : y;
  // exp(y) = 2^n exp(f), n = round(y / ln 2) (1.5 2^52 rounding trick), |f| <= ln2 / 2
  constexpr double kRound = 6755399441055744.0;
  const double n = (y * 1.44269504088896340736 + kRound) - kRound;
  const double f = (y - n * kLn2Hi) - n * kLn2Lo;
  double q = 1.0 / 6227020800.0;  // 1/13!
  q = q * f + 1.0 / 479001600.0;
  q = q * f + 1.0 / 39916800.0;
  q = q * f + 1.0 / 3628800.0;
  q = q * f + 1.0 / 362880.0;
  q = q * f + 1.0 / 40320.0;
  q = q * f + 1.0 / 5040.0;
  q = q * f + 1.0 / 720.0;
  q = q * f + 1.0 / 120.0;
  q = q * f + 1.0 / 24.0;
  q = q * f + 1.0 / 6.0;
  q = q * f + 0.5;
  q = q * f + 1.0;
  q = q * f + 1.0;
  // 2^n from the low bits of n + 2^52 + 1023 (n in [-1021, 0])
  const auto scale =
      std::bit_cast<double>((std::bit_cast<std::uint64_t>(n + (kTwo52 + 1023.0)) & 0x7ffULL) << 52);
  return x > 0.0 ? q * scale : 0.0;
}

/// Pair constants of one evaluation.
struct PairConsts {
  double inv_rc;     ///< 1 / r_c
  double rcc2;       ///< r_cc^2
  double inv_rcc;    ///< 1 / r_cc
  double a;          ///< conservative amplitude
  double gamma;      ///< dissipative coefficient
  double half_s1;    ///< exponent of w_R
  double sigma_dt;   ///< sigma / sqrt(dt), 0 = no noise
  double kernel_w0;  ///< Lucy alpha_D (W(0)) for the density sum
};

/// Structure-of-arrays block of the accepted pairs of one particle i (r_ij below the cutoff).
struct PairBlock {
  std::vector<std::uint32_t> j;
  std::vector<double> d[3];   ///< x_i - x_j (minimum image)
  std::vector<double> dv[3];  ///< v_i - v_j
  std::vector<double> r2;
  std::vector<double> s;    ///< F_ij / r_ij [force/length]
  std::vector<double> w;    ///< density kernel W(r_ij)
  std::vector<double> wdc;  ///< Fickian weight (1 - r/r_cc)^2, 0 beyond r_cc
  std::vector<float> z[4];  ///< pair_noise_numbers output
  void reserve(std::size_t m) {
    const std::size_t cap = m > 0 ? m : 1;
    if (j.size() >= cap) return;
    j.resize(cap);
    for (auto* v : {&d[0], &d[1], &d[2], &dv[0], &dv[1], &dv[2], &r2, &s, &w, &wdc}) v->resize(cap);
    for (auto& zz : z) zz.resize(cap);
  }
};

/// Fills b.wdc (and, unless flux_only, b.s and b.w) for k < m from b.d, b.dv, b.r2 and the
/// unit-variance noise xi[k] (ignored when sigma_dt = 0).
template <int D>
void pair_scalars(const PairConsts& c, std::size_t m, bool flux_only, const float* xi,
                  PairBlock& b);

}  // namespace sadr::fluid::tdpd
