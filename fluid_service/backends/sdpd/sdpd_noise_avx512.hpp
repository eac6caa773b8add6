// SPDX-License-Identifier: MIT
/// \file sdpd_noise_avx512.hpp
/// An AVX-512 build of pair_noise_numbers (core pair_noise_batch.cpp, whose clones stop at
/// AVX2) for the half-pair path; included by sdpd_rates.cpp (and its test) only. Same
/// numbers bit for bit: the same Philox4x32-10 rounds and the same single-precision
/// Box-Muller operations in the same order, no FMA contraction (optimize attribute), and the
/// square root by _mm512_sqrt_ps (IEEE, correctly rounded like sqrtss) because GCC does not
/// vectorise std::sqrt in this translation unit (errno; the core file has -fno-math-errno).
/// Tested against pair_noise_numbers (sdpd_half_pairs_test.cpp). 16 lanes instead of 8.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>

#include "sadr/common/rng.hpp"
#include "sadr/fluid/fluid_model.hpp"

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && \
    !defined(__SANITIZE_ADDRESS__)
#define SADR_NOISE_AVX512 1
#include <immintrin.h>
#endif

namespace sadr::fluid {

#ifdef SADR_NOISE_AVX512

/// Whether pair_noise_numbers_avx512 can run on this CPU.
inline bool noise_avx512_available() {
  static const bool cpu = __builtin_cpu_supports("avx512f") != 0;
  return cpu;
}

// Attributes on each function: a pragma region does not reach inlined/instantiated code.
#define SADR_NOISE_FN __attribute__((target("avx512f"), optimize("fp-contract=off")))

namespace noise_detail {

// Cephes logf for u in (0, 1], branch-free (identical to pair_noise_batch.cpp).
SADR_NOISE_FN inline float log_unit(float u) {
  const auto bits = std::bit_cast<std::int32_t>(u);
  float e = static_cast<float>(((bits >> 23) & 0xff) - 126);
  const std::int32_t mbits = (bits & 0x007fffff) | 0x3f000000;
  const std::int32_t small = -static_cast<std::int32_t>(mbits < 0x3f3504f3);
  e = e - static_cast<float>(small & 1);
  const float m = std::bit_cast<float>(mbits + (small & 0x00800000));
  const float x = m - 1.0f;
  const float z = x * x;
  float y = 7.0376836292e-2f;
  y = y * x - 1.1514610310e-1f;
  y = y * x + 1.1676998740e-1f;
  y = y * x - 1.2420140846e-1f;
  y = y * x + 1.4249322787e-1f;
  y = y * x - 1.6668057665e-1f;
  y = y * x + 2.0000714765e-1f;
  y = y * x - 2.4999993993e-1f;
  y = y * x + 3.3333331174e-1f;
  y = y * x * z;
  y = y + -2.12194440e-4f * e;
  y = y + -0.5f * z;
  return (x + y) + 0.693359375f * e;
}

// Box-Muller without the square root: r^2 (clamped at 0) and the unit vector (c, s).
SADR_NOISE_FN inline void box_muller_parts(std::uint32_t a, std::uint32_t b, float& r2_out,
                                           float& c_out, float& s_out) {
  const float u = static_cast<float>(static_cast<std::int32_t>(((a >> 9) << 1) | 1U)) * 0x1.0p-24f;
  const float r2 = -2.0f * log_unit(u);
  r2_out = r2 > 0.0f ? r2 : 0.0f;
  const float t = static_cast<float>(static_cast<std::int32_t>(b >> 8)) * 0x1.0p-24f - 0.5f;
  const float x = t * 1.57079632679489661923f;
  const float z = x * x;
  float sn = -1.9515295891e-4f;
  sn = sn * z + 8.3321608736e-3f;
  sn = sn * z - 1.6666654611e-1f;
  sn = sn * z * x + x;
  float cs = 2.443315711809948e-5f;
  cs = cs * z - 1.388731625493765e-3f;
  cs = cs * z + 4.166664568298827e-2f;
  cs = cs * z * z - 0.5f * z + 1.0f;
  const std::uint32_t odd = 0U - (b & 1U);
  const std::uint32_t neg = (b & 2U) << 30;
  const std::uint32_t cb = std::bit_cast<std::uint32_t>(cs), sb = std::bit_cast<std::uint32_t>(sn);
  c_out = std::bit_cast<float>(((cb & ~odd) | ((sb ^ 0x80000000U) & odd)) ^ neg);
  s_out = std::bit_cast<float>(((sb & ~odd) | (cb & odd)) ^ neg);
}

// o0 = sqrt(r2) c, o1 = sqrt(r2) s for k < m (masked tail).
SADR_NOISE_FN inline void scale_by_radius(const float* r2, const float* c, const float* s,
                                          std::size_t m, float* o0, float* o1) {
  for (std::size_t k = 0; k < m; k += 16) {
    const auto live = static_cast<__mmask16>(m - k >= 16 ? 0xFFFFU : (1U << (m - k)) - 1U);
    const __m512 r = _mm512_maskz_sqrt_ps(live, _mm512_maskz_loadu_ps(live, r2 + k));
    _mm512_mask_storeu_ps(o0 + k, live, _mm512_mul_ps(r, _mm512_maskz_loadu_ps(live, c + k)));
    _mm512_mask_storeu_ps(o1 + k, live, _mm512_mul_ps(r, _mm512_maskz_loadu_ps(live, s + k)));
  }
}

}  // namespace noise_detail

/// pair_noise_numbers (pair_noise_batch.hpp), AVX-512: identical output.
SADR_NOISE_FN inline void pair_noise_numbers_avx512(std::uint64_t seed, std::uint64_t step,
                                                    std::uint32_t i, const std::uint32_t* j,
                                                    std::size_t n, NoiseDistribution distribution,
                                                    float* z0, float* z1, float* z2, float* z3) {
  const bool gaussian = distribution == NoiseDistribution::kGaussian;
  const auto k0 = static_cast<std::uint32_t>(seed);
  const auto k1 = static_cast<std::uint32_t>(seed >> 32);
  const auto c2 = static_cast<std::uint32_t>(step);
  const std::uint32_t c3 = (static_cast<std::uint32_t>(rng::Purpose::kPairNoise) << 24) |
                           static_cast<std::uint32_t>((step >> 32) & 0xFFFFU);
  constexpr std::size_t kChunk = 64;
  alignas(64) std::uint32_t b0[kChunk], b1[kChunk], b2[kChunk], b3[kChunk];
  alignas(64) float ra[kChunk], ca[kChunk], sa[kChunk], rb[kChunk], cb[kChunk], sb[kChunk];
  for (std::size_t base = 0; base < n; base += kChunk) {
    const std::size_t m = n - base < kChunk ? n - base : kChunk;
    // Whole vectors of 16 lanes (padding lanes repeat the last pair and are not stored): a
    // 2D particle has ~12 pairs per evaluation, and GCC 12 would run a partial vector as a
    // scalar epilogue (measured: slower than the 8-lane AVX2 clone in 2D without this).
    const std::size_t mpad = (m + 15) / 16 * 16;
    alignas(64) std::uint32_t jc[kChunk];
    for (std::size_t k = 0; k < mpad; ++k) jc[k] = j[base + (k < m ? k : m - 1)];
    for (std::size_t k = 0; k < mpad; ++k) {  // Philox4x32-10, one pair per lane
      const std::uint32_t jj = jc[k];
      std::uint32_t x0 = i < jj ? i : jj, x1 = i < jj ? jj : i, x2 = c2, x3 = c3;
      std::uint32_t key0 = k0, key1 = k1;
#pragma GCC unroll 10
      for (int round = 0; round < 10; ++round) {
        const std::uint64_t p0 = std::uint64_t{0xD2511F53U} * x0;
        const std::uint64_t p1 = std::uint64_t{0xCD9E8D57U} * x2;
        const auto y0 = static_cast<std::uint32_t>(p1 >> 32) ^ x1 ^ key0;
        const auto y2 = static_cast<std::uint32_t>(p0 >> 32) ^ x3 ^ key1;
        x1 = static_cast<std::uint32_t>(p1);
        x3 = static_cast<std::uint32_t>(p0);
        x0 = y0;
        x2 = y2;
        key0 += 0x9E3779B9U;
        key1 += 0xBB67AE85U;
      }
      b0[k] = x0;
      b1[k] = x1;
      b2[k] = x2;
      b3[k] = x3;
    }
    if (gaussian) {
      for (std::size_t k = 0; k < mpad; ++k)
        noise_detail::box_muller_parts(b0[k], b1[k], ra[k], ca[k], sa[k]);
      for (std::size_t k = 0; k < mpad; ++k)
        noise_detail::box_muller_parts(b2[k], b3[k], rb[k], cb[k], sb[k]);
      noise_detail::scale_by_radius(ra, ca, sa, m, z0 + base, z1 + base);
      noise_detail::scale_by_radius(rb, cb, sb, m, z2 + base, z3 + base);
    } else {
      constexpr float s = 3.4641016151377546f;  // 2 sqrt(3)
      auto uni = [](std::uint32_t b) SADR_NOISE_FN {
        return s * (static_cast<float>(static_cast<std::int32_t>(b >> 8)) * 0x1.0p-24f +
                    (0x1.0p-25f - 0.5f));
      };
      for (std::size_t k = 0; k < m; ++k) {
        z0[base + k] = uni(b0[k]);
        z1[base + k] = uni(b1[k]);
        z2[base + k] = uni(b2[k]);
        z3[base + k] = uni(b3[k]);
      }
    }
  }
}

#undef SADR_NOISE_FN

#else

inline bool noise_avx512_available() {
  return false;
}
inline void pair_noise_numbers_avx512(std::uint64_t, std::uint64_t, std::uint32_t,
                                      const std::uint32_t*, std::size_t, NoiseDistribution, float*,
                                      float*, float*, float*) {}

#endif

}  // namespace sadr::fluid
