// SPDX-License-Identifier: MIT
#include "sadr/fluid/pair_noise_batch.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include "sadr/common/rng.hpp"

namespace sadr::fluid {

namespace {

// ln(u) for u in (0, 1], Cephes logf (branch-free form).
inline float log_unit(float u) {
  const auto bits = std::bit_cast<std::int32_t>(u);
  float e = static_cast<float>(((bits >> 23) & 0xff) - 126);

  const std::int32_t mbits = (bits & 0x007fffff) | 0x3f000000;  // m in [0.5, 1)
  // m < sqrt(1/2): use 2m - 1 and e - 1 (branch-free: the mantissa of 2m is that of m).
  const std::int32_t small = -static_cast<std::int32_t>(mbits < 0x3f3504f3);  // 0 or -1
  e = e - static_cast<float>(small & 1);
  const float m = std::bit_cast<float>(mbits + (small & 0x00800000));  // m or 2m
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

// One Box-Muller pair from two words: (r cos th, r sin th).
inline void box_muller(std::uint32_t a, std::uint32_t b, float& c_out, float& s_out) {
  const float u = static_cast<float>(static_cast<std::int32_t>(((a >> 9) << 1) | 1U)) * 0x1.0p-24f;
  const float r2 = -2.0f * log_unit(u);
  const float r = std::sqrt(r2 > 0.0f ? r2 : 0.0f);
  // angle offset in [-pi/4, pi/4)
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
  // rotate by q = b & 3 quarter turns: (c, s) -> (-s, c) for odd q, negate both for q >= 2
  const std::uint32_t odd = 0U - (b & 1U);
  const std::uint32_t neg = (b & 2U) << 30;
  const std::uint32_t cb = std::bit_cast<std::uint32_t>(cs), sb = std::bit_cast<std::uint32_t>(sn);
  const std::uint32_t c1 = ((cb & ~odd) | ((sb ^ 0x80000000U) & odd)) ^ neg;
  const std::uint32_t s1 = ((sb & ~odd) | (cb & odd)) ^ neg;
  c_out = r * std::bit_cast<float>(c1);
  s_out = r * std::bit_cast<float>(s1);
}

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && \
    !defined(__SANITIZE_ADDRESS__)
// avx512f: 16 lanes; with the padding below it is faster than avx2 in 3D (+8 %, measured
// for the SDPD half-pair path) and not slower in 2D. This file is compiled with
// -ffp-contract=off and -fno-math-errno, so every clone gives the same bits.
#define SADR_NOISE_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define SADR_NOISE_CLONES
#endif

SADR_NOISE_CLONES
void numbers_impl(std::uint64_t seed, std::uint64_t step, std::uint32_t i_one,
                  const std::uint32_t* i_lanes, const std::uint32_t* j, std::size_t n,
                  bool gaussian, float* z0, float* z1, float* z2, float* z3) {
  const auto k0 = static_cast<std::uint32_t>(seed);
  const auto k1 = static_cast<std::uint32_t>(seed >> 32);
  const auto c2 = static_cast<std::uint32_t>(step);
  const std::uint32_t c3 = (static_cast<std::uint32_t>(rng::Purpose::kPairNoise) << 24) |
                           static_cast<std::uint32_t>((step >> 32) & 0xFFFFU);
  constexpr std::size_t kChunk = 64;
  alignas(64) std::uint32_t b0[kChunk], b1[kChunk], b2[kChunk], b3[kChunk];
  alignas(64) std::uint32_t ic[kChunk], jc[kChunk];
  alignas(64) float t0[kChunk], t1[kChunk], t2[kChunk], t3[kChunk];
  for (std::size_t base = 0; base < n; base += kChunk) {
    const std::size_t m = n - base < kChunk ? n - base : kChunk;
    // Whole vectors of 16 lanes: padding lanes repeat the last pair and are not stored.
    // A 2D particle has ~12 pairs per evaluation, and GCC 12 runs a partial vector as a
    // scalar epilogue (measured: the avx512f clone was slower than avx2 in 2D without it).
    const std::size_t mpad = (m + 15) / 16 * 16;
    for (std::size_t k = 0; k < mpad; ++k) {
      const std::size_t src = base + (k < m ? k : m - 1);
      jc[k] = j[src];
      ic[k] = i_lanes ? i_lanes[src] : i_one;
    }
    for (std::size_t k = 0; k < mpad; ++k) {  // Philox4x32-10 (rng::Philox4x32), one pair per lane
      const std::uint32_t i = ic[k], jj = jc[k];
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
      for (std::size_t k = 0; k < mpad; ++k) box_muller(b0[k], b1[k], t0[k], t1[k]);
      for (std::size_t k = 0; k < mpad; ++k) box_muller(b2[k], b3[k], t2[k], t3[k]);
    } else {
      constexpr float s = 3.4641016151377546f;  // 2 sqrt(3)
      auto uni = [](std::uint32_t b) {
        return s * (static_cast<float>(static_cast<std::int32_t>(b >> 8)) * 0x1.0p-24f +
                    (0x1.0p-25f - 0.5f));
      };
      for (std::size_t k = 0; k < mpad; ++k) {
        t0[k] = uni(b0[k]);
        t1[k] = uni(b1[k]);
        t2[k] = uni(b2[k]);
        t3[k] = uni(b3[k]);
      }
    }
    std::copy_n(t0, m, z0 + base);
    std::copy_n(t1, m, z1 + base);
    std::copy_n(t2, m, z2 + base);
    std::copy_n(t3, m, z3 + base);
  }
}

}  // namespace

void pair_noise_numbers(std::uint64_t seed, std::uint64_t step, std::uint32_t i,
                        const std::uint32_t* j, std::size_t n, NoiseDistribution distribution,
                        float* z0, float* z1, float* z2, float* z3) {
  numbers_impl(seed, step, i, nullptr, j, n, distribution == NoiseDistribution::kGaussian, z0, z1,
               z2, z3);
}

void pair_noise_numbers_lanes(std::uint64_t seed, std::uint64_t step, const std::uint32_t* i,
                              const std::uint32_t* j, std::size_t n, NoiseDistribution distribution,
                              float* z0, float* z1, float* z2, float* z3) {
  numbers_impl(seed, step, 0, i, j, n, distribution == NoiseDistribution::kGaussian, z0, z1, z2,
               z3);
}

}  // namespace sadr::fluid
