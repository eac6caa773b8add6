// SPDX-License-Identifier: MIT
// Built with -ffp-contract=off (CMakeLists.txt): the scalar and the AVX-512F
// filter must round every product and sum separately to give the same bits.
#include "graph_filter.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
// GCC 12's avx512fintrin.h builds "undefined" vectors as `__m512d y = y;`, which
// -Wmaybe-uninitialized reports wherever the casts/extracts below are inlined.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <immintrin.h>
#define SADR_GRAPH_AVX512 1
#endif

namespace sadr::ssa::detail {

namespace {

using Edge = DiffusionGraph::Edge;

/// The lane reduction of graph_filter.hpp: ((s0 + s4) + (s2 + s6)) + ((s1 + s5) + (s3 + s7)).
inline double sum8_lanes(const double* s) {
  const double t0 = s[0] + s[4], t1 = s[1] + s[5], t2 = s[2] + s[6], t3 = s[3] + s[7];
  return (t0 + t2) + (t1 + t3);
}

template <int D>
std::uint32_t filter_scalar(const FilterParams& p, std::size_t i0, std::size_t i1, Edge* e,
                            const FilterOutputs& o) {
  // Per-row scratch: r2 and F reg of every candidate, computed in branch-free loops
  // the compiler vectorises (two at a time with SSE2; -fno-math-errno), then
  // compressed to the edges with r < h.
  thread_local std::vector<double> r2buf, fbuf;
  std::uint32_t max_row = 0;
  for (std::size_t i = i0; i < i1; ++i) {
    max_row = std::max(max_row, p.cand_start[i + 1] - p.cand_start[i]);
  }
  if (r2buf.size() < max_row) r2buf.resize(max_row), fbuf.resize(max_row);
  double* r2s = r2buf.data();
  double* fs = fbuf.data();
  const double* x = p.x;
  const double *m = p.m, *rho = p.rho, *vol = p.vol;
  std::uint32_t out = 0;
  for (std::size_t i = i0; i < i1; ++i) {
    double xi[3] = {0, 0, 0};
    for (int a = 0; a < D; ++a) xi[a] = x[D * i + a];
    const std::uint32_t kb = p.cand_start[i], ks = p.cand_split[i], ke = p.cand_start[i + 1];
    const std::uint32_t len_row = ke - kb;
    const std::uint32_t* row = p.cand + kb;
    for (std::uint32_t k = 0; k < len_row; ++k) {
      const double* xj = x + static_cast<std::size_t>(D) * row[k];
      double r2 = 0;
      for (int a = 0; a < D; ++a) {
        // Branch-free minimum image: dx - len, dx or dx + len.
        double dx = xi[a] - xj[a];
        dx -= p.len[a] * static_cast<double>(static_cast<int>(dx > p.half[a]) -
                                             static_cast<int>(dx < -p.half[a]));
        r2 += dx * dx;
      }
      r2s[k] = r2;
    }
    for (std::uint32_t k = 0; k < len_row; ++k) {
      const double r2 = r2s[k];
      const double one_q = 1.0 - std::sqrt(r2) * p.inv_h;  // garbage beyond h: dropped below
      fs[k] = (r2 / (r2 + p.eps_h2)) * (p.f0 * one_q * one_q);
    }
    const double mi = m[i], rhoi = rho[i], vi = vol[i];
    double wall_r2 = std::numeric_limits<double>::infinity();
    // Keeps the candidates of [k0, k1) with r < h and a positive weight; returns
    // their weight sum (row order). Two calls: non-wall part, then wall part.
    auto keep = [&](std::uint32_t k0, std::uint32_t k1, auto to_wall) {
      double lane[8] = {0, 0, 0, 0, 0, 0, 0, 0};
      const std::uint32_t first = out;
      for (std::uint32_t k = k0; k < k1; ++k) {
        const double r2 = r2s[k];
        if (!(r2 < p.h2)) continue;
        if constexpr (decltype(to_wall)::value) wall_r2 = std::min(wall_r2, r2);
        const std::uint32_t j = row[k];
        const double reg_f = fs[k];
        double w_ij = 0, w_ji = 0;
        if (p.symmetric) {
          // drawert2019 eq 28: D_ij = 2 m_i m_j/(m_i+m_j) (rho_i+rho_j)/(rho_i rho_j) reg F_ij.
          w_ij = w_ji =
              2.0 * (mi * m[j] / (mi + m[j])) * ((rhoi + rho[j]) / (rhoi * rho[j])) * reg_f;
        } else {
          // Volume-consistent: D_ij = 2 V_j F_ij reg, so D_ij V_i = D_ji V_j.
          w_ij = 2.0 * vol[j] * reg_f;
          w_ji = 2.0 * vi * reg_f;
        }
        if (!(w_ij > 0 && w_ji > 0)) continue;  // coincident particles (reg = 0): no edge
        lane[(out - first) % 8] += w_ij;
        e[out++] = Edge{w_ij, j};
      }
      return sum8_lanes(lane);
    };
    o.row_start[i] = out;
    const double sum_nowall = keep(0, ks - kb, std::false_type{});
    o.split[i] = out;
    const double sum_wall = keep(ks - kb, len_row, std::true_type{});
    o.sum_nowall[i] = sum_nowall;
    o.sum_all[i] = sum_nowall + sum_wall;
    o.wall_distance[i] = std::sqrt(wall_r2);
  }
  return out;
}

#ifdef SADR_GRAPH_AVX512

/// v[stride js[l]] in lane l.
__attribute__((target("avx512f"))) inline __m512d load8(const double* v, const std::uint32_t* js,
                                                        std::size_t stride) {
  return _mm512_set_pd(v[stride * js[7]], v[stride * js[6]], v[stride * js[5]], v[stride * js[4]],
                       v[stride * js[3]], v[stride * js[2]], v[stride * js[1]], v[stride * js[0]]);
}

/// filter_scalar() 8 candidates at a time; every lane performs the scalar
/// path's operations in the same order (intrinsics, no contraction).
template <int D>
__attribute__((target("avx512f"))) std::uint32_t filter_avx512(const FilterParams& p,
                                                               std::size_t i0, std::size_t i1,
                                                               Edge* e, const FilterOutputs& o) {
  const __m512d zero = _mm512_setzero_pd(), one = _mm512_set1_pd(1.0), two = _mm512_set1_pd(2.0);
  const __m512d h2 = _mm512_set1_pd(p.h2), eps = _mm512_set1_pd(p.eps_h2);
  const __m512d inv_h = _mm512_set1_pd(p.inv_h), f0 = _mm512_set1_pd(p.f0);
  __m512d len[3], half[3], nhalf[3];
  for (int a = 0; a < D; ++a) {
    len[a] = _mm512_set1_pd(p.len[a]);
    half[a] = _mm512_set1_pd(p.half[a]);
    nhalf[a] = _mm512_set1_pd(-p.half[a]);
  }
  // Interleaving 8 (weight, target) pairs into 12-byte Edge records: 32-bit word w
  // of the output is weight word 2k + r (r = w % 3 < 2) or target k (r == 2), k = w / 3.
  alignas(64) std::int32_t perm[32];
  for (int w = 0; w < 32; ++w) perm[w] = w % 3 < 2 ? 2 * (w / 3) + w % 3 : 16 + w / 3;
  const __m512i perm_lo = _mm512_load_si512(perm), perm_hi = _mm512_load_si512(perm + 16);
  const __m512i even = _mm512_setr_epi64(0, 2, 4, 6, 8, 10, 12, 14);
  const __m512i iota = _mm512_setr_epi64(0, 1, 2, 3, 4, 5, 6, 7), seven = _mm512_set1_epi64(7);
  const __m512i odd = _mm512_setr_epi64(1, 3, 5, 7, 9, 11, 13, 15);
  const double* x = p.x;
  std::uint32_t out = 0;
  for (std::size_t i = i0; i < i1; ++i) {
    __m512d xi[3];
    for (int a = 0; a < D; ++a) xi[a] = _mm512_set1_pd(x[D * i + a]);
    const std::uint32_t kb = p.cand_start[i], ks = p.cand_split[i], ke = p.cand_start[i + 1];
    const __m512d mi = _mm512_set1_pd(p.m[i]), rhoi = _mm512_set1_pd(p.rho[i]);
    const __m512d two_vi = _mm512_set1_pd(2.0 * p.vol[i]);
    __m512d wall_r2 = _mm512_set1_pd(std::numeric_limits<double>::infinity());
    // Two parts of the row (non-wall targets [kb, ks), then wall targets [ks, ke)),
    // each with its weight sum in row order, like filter_scalar()'s keep(). A loop,
    // not a lambda: a lambda would not inherit the avx512f target.
    double sums[2] = {0, 0};
    o.row_start[i] = out;
    for (int pass = 0; pass < 2; ++pass) {
      const bool to_wall = pass == 1;
      if (to_wall) o.split[i] = out;
      const std::uint32_t k0 = to_wall ? ks : kb, k1 = to_wall ? ke : ks;
      __m512d acc = zero;  // the part's weight sums: its edge q in lane q % 8
      const std::uint32_t first = out;
      for (std::uint32_t k = k0; k < k1; k += 8) {
        const std::uint32_t rem = k1 - k;
        const __mmask8 lanes = rem >= 8 ? 0xFF : static_cast<__mmask8>((1u << rem) - 1u);
        const __m512i idx16 = _mm512_maskz_loadu_epi32(lanes, p.cand + k);
        // Targets by scalar loads; lanes past the row read the next row's targets (or
        // the kCandSlack indices after the last row), valid particles whose results
        // `lanes` masks off. 8 scalar loads and a few shuffles beat a gather: 95 vs
        // 125 ns/voxel for the filter in 2D on Zen 4, 72 vs 87 on this machine's Zen 5.
        std::uint32_t js[8];
        for (int l = 0; l < 8; ++l) js[l] = p.cand[k + l];
        __m512d xjs[3];
        if constexpr (D == 2) {
          // 2D: the (x, y) pairs by 128-bit loads, split by two permutes.
          __m128d pr[8];
          for (int l = 0; l < 8; ++l) pr[l] = _mm_loadu_pd(x + 2 * static_cast<std::size_t>(js[l]));
          const __m512d lo = _mm512_insertf64x4(
              _mm512_castpd256_pd512(_mm256_insertf128_pd(_mm256_castpd128_pd256(pr[0]), pr[1], 1)),
              _mm256_insertf128_pd(_mm256_castpd128_pd256(pr[2]), pr[3], 1), 1);
          const __m512d hi = _mm512_insertf64x4(
              _mm512_castpd256_pd512(_mm256_insertf128_pd(_mm256_castpd128_pd256(pr[4]), pr[5], 1)),
              _mm256_insertf128_pd(_mm256_castpd128_pd256(pr[6]), pr[7], 1), 1);
          xjs[0] = _mm512_permutex2var_pd(lo, even, hi);
          xjs[1] = _mm512_permutex2var_pd(lo, odd, hi);
        } else {
          for (int a = 0; a < D; ++a) xjs[a] = load8(x + a, js, D);
        }
        __m512d r2 = zero;
        for (int a = 0; a < D; ++a) {
          const __m512d xj = xjs[a];
          __m512d dx = _mm512_sub_pd(xi[a], xj);
          // dx - len if dx > half, dx + len if dx < -half (= dx - len * (-1) exactly).
          const __mmask8 gt = _mm512_cmp_pd_mask(dx, half[a], _CMP_GT_OQ);
          const __mmask8 lt = _mm512_cmp_pd_mask(dx, nhalf[a], _CMP_LT_OQ);
          dx = _mm512_mask_sub_pd(dx, gt, dx, len[a]);
          dx = _mm512_mask_add_pd(dx, lt, dx, len[a]);
          r2 = _mm512_add_pd(r2, _mm512_mul_pd(dx, dx));
        }
        __mmask8 keep = _mm512_mask_cmp_pd_mask(lanes, r2, h2, _CMP_LT_OQ);
        if (!keep) continue;
        if (to_wall) wall_r2 = _mm512_mask_min_pd(wall_r2, keep, wall_r2, r2);
        const __m512d one_q = _mm512_sub_pd(one, _mm512_mul_pd(_mm512_sqrt_pd(r2), inv_h));
        const __m512d reg_f = _mm512_mul_pd(_mm512_div_pd(r2, _mm512_add_pd(r2, eps)),
                                            _mm512_mul_pd(_mm512_mul_pd(f0, one_q), one_q));
        __m512d w_ij, w_ji;
        if (p.symmetric) {
          const __m512d mj = load8(p.m, js, 1), rhoj = load8(p.rho, js, 1);
          const __m512d mm = _mm512_div_pd(_mm512_mul_pd(mi, mj), _mm512_add_pd(mi, mj));
          const __m512d rr = _mm512_div_pd(_mm512_add_pd(rhoi, rhoj), _mm512_mul_pd(rhoi, rhoj));
          w_ij = w_ji = _mm512_mul_pd(_mm512_mul_pd(_mm512_mul_pd(two, mm), rr), reg_f);
        } else {
          const __m512d vj = load8(p.vol, js, 1);
          w_ij = _mm512_mul_pd(_mm512_mul_pd(two, vj), reg_f);
          w_ji = _mm512_mul_pd(two_vi, reg_f);
        }
        keep = _mm512_mask_cmp_pd_mask(keep, w_ij, zero, _CMP_GT_OQ);
        keep = _mm512_mask_cmp_pd_mask(keep, w_ji, zero, _CMP_GT_OQ);
        // Register compress (the memory form is slow on some cores), then all 8
        // records stored; those past the count are overwritten or trimmed later.
        const __m512d wc = _mm512_maskz_compress_pd(keep, w_ij);
        const __m512i tc = _mm512_maskz_compress_epi32(keep, idx16);
        const __m512i wci = _mm512_castpd_si512(wc);
        char* dst = reinterpret_cast<char*>(e + out);
        _mm512_storeu_si512(dst, _mm512_permutex2var_epi32(wci, perm_lo, tc));
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(dst + 64),
                            _mm512_castsi512_si256(_mm512_permutex2var_epi32(wci, perm_hi, tc)));
        // Compressed lane l is the part's edge out - first + l: rotated into its lane.
        const __m512i rot = _mm512_and_si512(
            _mm512_sub_epi64(iota, _mm512_set1_epi64(static_cast<long long>(out - first))), seven);
        acc = _mm512_add_pd(acc, _mm512_permutexvar_pd(rot, wc));
        const int cnt = __builtin_popcount(keep);
        out += static_cast<std::uint32_t>(cnt);
      }
      // sum8_lanes(): (s0 + s4, s1 + s5, s2 + s6, s3 + s7), then (t0 + t2, t1 + t3), then u0 + u1.
      const __m256d t = _mm256_add_pd(_mm512_castpd512_pd256(acc), _mm512_extractf64x4_pd(acc, 1));
      const __m128d u = _mm_add_pd(_mm256_castpd256_pd128(t), _mm256_extractf128_pd(t, 1));
      sums[pass] = _mm_cvtsd_f64(_mm_add_sd(u, _mm_unpackhi_pd(u, u)));
    }
    o.sum_nowall[i] = sums[0];
    o.sum_all[i] = sums[0] + sums[1];
    // min is exact, so the lane order does not matter.
    o.wall_distance[i] = ks == ke ? std::numeric_limits<double>::infinity()
                                  : std::sqrt(_mm512_reduce_min_pd(wall_r2));
  }
  return out;
}

#endif  // SADR_GRAPH_AVX512

}  // namespace

bool filter_simd_available() {
#ifdef SADR_GRAPH_AVX512
  static const bool ok = __builtin_cpu_supports("avx512f");
  return ok;
#else
  return false;
#endif
}

std::uint32_t filter_rows(const FilterParams& p, std::size_t i0, std::size_t i1, Edge* e,
                          const FilterOutputs& o, bool simd) {
#ifdef SADR_GRAPH_AVX512
  if (simd && filter_simd_available()) {
    if (p.dim == 1) return filter_avx512<1>(p, i0, i1, e, o);
    if (p.dim == 2) return filter_avx512<2>(p, i0, i1, e, o);
    return filter_avx512<3>(p, i0, i1, e, o);
  }
#else
  (void)simd;
#endif
  if (p.dim == 1) return filter_scalar<1>(p, i0, i1, e, o);
  if (p.dim == 2) return filter_scalar<2>(p, i0, i1, e, o);
  return filter_scalar<3>(p, i0, i1, e, o);
}

}  // namespace sadr::ssa::detail
