// SPDX-License-Identifier: MIT
#include "graph_search.hpp"

#include <algorithm>
#include <array>

#include "graph_filter.hpp"  // filter_simd_available()

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#define SADR_GRAPH_AVX512 1
#endif

namespace sadr::ssa::detail {

namespace {

/// A contiguous range of cell-order slots [b, e) seen from particle i with one
/// periodic image shift (subtracted from x_i - x_j).
struct Run {
  std::uint32_t b, e;
  double s[3];
};

/// The 3^d cells around one cell as runs: neighbouring cells along x that are
/// adjacent in memory with the same shift are merged (3 runs per row in 2D away
/// from the periodic seams). Kept while consecutive particles share a cell (a
/// few in a row when indices follow space, as in lattice-built states).
struct Stencil {
  int cell[3] = {-1, -1, -1};
  int nr = 0;
  std::size_t total = 0;  ///< slots in all runs
  Run runs[27];
};

/// Loads particle i's coordinates into xi and returns the stencil of its cell
/// (recomputed only when the cell differs from the one in `st`).
template <int D>
const Stencil& stencil_for(const CellGrid& grid, const CellGrid::View& v, std::size_t i, double* xi,
                           Stencil& st) {
  int cell[3] = {0, 0, 0};
  for (int a = 0; a < D; ++a) {
    xi[a] = v.x[D * i + a];
    cell[a] = grid.coord(xi[a], a);
  }
  if (cell[0] == st.cell[0] && cell[1] == st.cell[1] && cell[2] == st.cell[2]) return st;
  for (int a = 0; a < 3; ++a) st.cell[a] = cell[a];
  std::array<std::array<int, 3>, 3> cand{};
  std::array<std::array<double, 3>, 3> shift{};
  std::array<int, 3> ncand{1, 1, 1};
  for (int a = 0; a < D; ++a) {
    const int c = cell[a];
    int k = 0;
    for (int off = -1; off <= 1; ++off) {
      int cc = c + off;
      double sh = 0;
      if (v.periodic[a]) {
        if (cc < 0) cc += v.nc[a], sh = -v.len[a];
        if (cc >= v.nc[a]) cc -= v.nc[a], sh = v.len[a];
      } else if (cc < 0 || cc >= v.nc[a]) {
        continue;
      }
      cand[a][k] = cc;
      shift[a][k] = sh;
      ++k;
    }
    ncand[a] = k;
  }
  Run* runs = st.runs;
  int nr = 0;
  std::size_t total = 0;
  const std::size_t nc0 = static_cast<std::size_t>(v.nc[0]),
                    nc1 = static_cast<std::size_t>(v.nc[1]);
  for (int iz = 0; iz < ncand[2]; ++iz) {
    for (int iy = 0; iy < ncand[1]; ++iy) {
      const std::size_t row = (static_cast<std::size_t>(cand[2][iz]) * nc1 + cand[1][iy]) * nc0;
      for (int ix = 0; ix < ncand[0]; ++ix) {
        const std::size_t c = row + static_cast<std::size_t>(cand[0][ix]);
        const std::uint32_t b = v.cell_start[c], e = v.cell_start[c + 1];
        if (b == e) continue;
        const double s[3] = {shift[0][ix], shift[1][iy], shift[2][iz]};
        total += e - b;
        if (nr > 0 && runs[nr - 1].e == b && runs[nr - 1].s[0] == s[0] &&
            runs[nr - 1].s[1] == s[1] && runs[nr - 1].s[2] == s[2]) {
          runs[nr - 1].e = e;
          continue;
        }
        runs[nr++] = Run{b, e, {s[0], s[1], s[2]}};
      }
    }
  }
  st.nr = nr;
  st.total = total;
  return st;
}

/// Sorts a short candidate row (insertion sort: ~40 indices in a few ascending runs).
void sort_short(std::uint32_t* v, std::size_t n) {
  if (n > 64) {
    std::sort(v, v + n);
    return;
  }
  for (std::size_t k = 1; k < n; ++k) {
    const std::uint32_t x = v[k];
    std::size_t q = k;
    for (; q > 0 && v[q - 1] > x; --q) v[q] = v[q - 1];
    v[q] = x;
  }
}

/// Room for `need` more entries at out[len..] (grown geometrically, never shrunk here).
inline std::uint32_t* room(std::vector<std::uint32_t>& out, std::size_t len, std::size_t need) {
  if (out.size() < len + need) out.resize(std::max(len + need, 2 * out.size()));
  return out.data() + len;
}

template <int D>
void search_scalar(const CellGrid& grid, const std::uint8_t* wall, std::size_t r0, std::size_t r1,
                   std::vector<std::uint32_t>& out, std::uint32_t* deg_nw, std::uint32_t* deg_w) {
  const CellGrid::View v = grid.view();
  thread_local std::vector<std::uint32_t> wbuf;
  std::size_t len = 0;
  Stencil st;
  for (std::size_t i = r0; i < r1; ++i) {
    double xi[3] = {0, 0, 0};
    const Stencil& sten = stencil_for<D>(grid, v, i, xi, st);
    const int nr = sten.nr;
    const std::size_t total = sten.total;
    const Run* runs = sten.runs;
    std::uint32_t* nw = room(out, len, total);
    if (wbuf.size() < total) wbuf.resize(total);
    std::uint32_t n_nw = 0, n_w = 0;
    for (int r = 0; r < nr; ++r) {
      for (std::uint32_t m = runs[r].b; m < runs[r].e; ++m) {
        // (x_i - x_j) - shift, as CellGrid::for_each_neighbor().
        const double dx = (xi[0] - v.xs[D * m]) - runs[r].s[0];
        double r2 = dx * dx;
        if constexpr (D >= 2) {
          const double dy = (xi[1] - v.xs[D * m + 1]) - runs[r].s[1];
          r2 += dy * dy;
        }
        if constexpr (D >= 3) {
          const double dz = (xi[2] - v.xs[D * m + 2]) - runs[r].s[2];
          r2 += dz * dz;
        }
        const std::uint32_t j = v.members[m];
        if (!(r2 < v.cut2) || j == i) continue;
        if (wall[j]) {
          wbuf[n_w++] = j;
        } else {
          nw[n_nw++] = j;
        }
      }
    }
    sort_short(nw, n_nw);
    sort_short(wbuf.data(), n_w);
    std::copy(wbuf.begin(), wbuf.begin() + n_w, nw + n_nw);
    deg_nw[i] = n_nw;
    deg_w[i] = n_w;
    len += n_nw + n_w;
  }
  out.resize(len);
}

#ifdef SADR_GRAPH_AVX512

inline __mmask16 first_lanes(std::size_t k) {
  return k >= 16 ? static_cast<__mmask16>(0xFFFF) : static_cast<__mmask16>((1u << k) - 1u);
}

/// Writes the n distinct values of v to o in ascending order: each value goes to
/// its rank (the number of smaller values, 3 vector compares), no branches on the
/// data. Rows longer than 48 use std::sort.
__attribute__((target("avx512f"))) void rank_sort(const std::uint32_t* v, std::size_t n,
                                                  std::uint32_t* o) {
  if (n > 48) {
    std::copy(v, v + n, o);
    std::sort(o, o + n);
    return;
  }
  const __m512i pad = _mm512_set1_epi32(-1);  // above every index (indices < 2^32 - 1)
  const __m512i z0 = _mm512_mask_loadu_epi32(pad, first_lanes(n), v);
  const __m512i z1 = _mm512_mask_loadu_epi32(pad, first_lanes(n > 16 ? n - 16 : 0), v + 16);
  const __m512i z2 = _mm512_mask_loadu_epi32(pad, first_lanes(n > 32 ? n - 32 : 0), v + 32);
  for (std::size_t k = 0; k < n; ++k) {
    const __m512i b = _mm512_set1_epi32(static_cast<int>(v[k]));
    const int r = __builtin_popcount(_mm512_cmplt_epu32_mask(z0, b)) +
                  __builtin_popcount(_mm512_cmplt_epu32_mask(z1, b)) +
                  __builtin_popcount(_mm512_cmplt_epu32_mask(z2, b));
    o[r] = v[k];
  }
}

/// search_scalar() 8 slots at a time: the same r^2 per pair (same operations and
/// order), survivors compressed in registers, rows sorted by rank_sort().
template <int D>
__attribute__((target("avx512f"))) void search_avx512(const CellGrid& grid,
                                                      const std::uint32_t* wall_cell,
                                                      std::size_t r0, std::size_t r1,
                                                      std::vector<std::uint32_t>& out,
                                                      std::uint32_t* deg_nw, std::uint32_t* deg_w) {
  const CellGrid::View v = grid.view();
  thread_local std::vector<std::uint32_t> nwbuf, wbuf;
  const __m512d cut2 = _mm512_set1_pd(v.cut2);
  // Coordinates of 8 consecutive slots: D contiguous loads of 8 doubles, then per
  // axis a two-source permute (elements < 16) and a masked permute of the third
  // register (3D). Element of lane l, axis a: D l + a.
  __m512i from_ab[3], from_c[3];
  __mmask8 use_c[3];
  for (int a = 0; a < D; ++a) {
    alignas(64) std::int64_t ab[8], c[8];
    use_c[a] = 0;
    for (int l = 0; l < 8; ++l) {
      const int e = D * l + a;
      ab[l] = e < 16 ? e : 0;
      c[l] = e >= 16 ? e - 16 : 0;
      if (e >= 16) use_c[a] = static_cast<__mmask8>(use_c[a] | (1u << l));
    }
    from_ab[a] = _mm512_load_si512(ab);
    from_c[a] = _mm512_load_si512(c);
  }
  std::size_t len = 0;
  Stencil st;
  for (std::size_t i = r0; i < r1; ++i) {
    double xi[3] = {0, 0, 0};
    const Stencil& sten = stencil_for<D>(grid, v, i, xi, st);
    const int nr = sten.nr;
    const std::size_t total = sten.total;
    const Run* runs = sten.runs;
    if (nwbuf.size() < total + 16) nwbuf.resize(total + 16), wbuf.resize(total + 16);
    std::uint32_t* nw = nwbuf.data();
    std::uint32_t* w = wbuf.data();
    std::uint32_t n_nw = 0, n_w = 0;
    const __m512i self = _mm512_set1_epi32(static_cast<int>(i));
    __m512d xiv[3];
    for (int a = 0; a < D; ++a) xiv[a] = _mm512_set1_pd(xi[a]);
    for (int r = 0; r < nr; ++r) {
      __m512d s[3];
      for (int a = 0; a < D; ++a) s[a] = _mm512_set1_pd(runs[r].s[a]);
      for (std::uint32_t m = runs[r].b; m < runs[r].e; m += 8) {
        const __mmask8 lanes = static_cast<__mmask8>(first_lanes(runs[r].e - m));
        const __m512i mem = _mm512_maskz_loadu_epi32(lanes, v.members + m);
        const __m512i wl = _mm512_maskz_loadu_epi32(lanes, wall_cell + m);
        const std::size_t valid =
            static_cast<std::size_t>(D) * std::min<std::uint32_t>(runs[r].e - m, 8);
        __m512d q[3];
        for (int k = 0; k < D; ++k) {
          const std::size_t lo = 8 * static_cast<std::size_t>(k);
          const __mmask8 mk = valid > lo ? static_cast<__mmask8>(first_lanes(valid - lo)) : 0;
          q[k] = _mm512_maskz_loadu_pd(mk, v.xs + D * static_cast<std::size_t>(m) + lo);
        }
        __m512d r2 = _mm512_setzero_pd();
        for (int a = 0; a < D; ++a) {
          __m512d xj = q[0];
          if constexpr (D >= 2) xj = _mm512_permutex2var_pd(q[0], from_ab[a], q[1]);
          if constexpr (D >= 3) xj = _mm512_mask_permutexvar_pd(xj, use_c[a], from_c[a], q[2]);
          const __m512d dx = _mm512_sub_pd(_mm512_sub_pd(xiv[a], xj), s[a]);
          r2 = a == 0 ? _mm512_mul_pd(dx, dx) : _mm512_add_pd(r2, _mm512_mul_pd(dx, dx));
        }
        const __mmask16 keep =
            static_cast<__mmask16>(_mm512_mask_cmp_pd_mask(lanes, r2, cut2, _CMP_LT_OQ) &
                                   _mm512_cmpneq_epi32_mask(mem, self));
        const __mmask16 is_w = _mm512_test_epi32_mask(wl, wl);
        const __mmask16 k_nw = keep & static_cast<__mmask16>(~is_w), k_w = keep & is_w;
        _mm512_storeu_si512(nw + n_nw, _mm512_maskz_compress_epi32(k_nw, mem));
        n_nw += static_cast<std::uint32_t>(__builtin_popcount(k_nw));
        if (k_w) {
          _mm512_storeu_si512(w + n_w, _mm512_maskz_compress_epi32(k_w, mem));
          n_w += static_cast<std::uint32_t>(__builtin_popcount(k_w));
        }
      }
    }
    std::uint32_t* o = room(out, len, n_nw + n_w);
    rank_sort(nw, n_nw, o);
    rank_sort(w, n_w, o + n_nw);
    deg_nw[i] = n_nw;
    deg_w[i] = n_w;
    len += n_nw + n_w;
  }
  out.resize(len);
}

#endif  // SADR_GRAPH_AVX512

}  // namespace

void search_rows(const CellGrid& grid, const std::uint8_t* wall, const std::uint32_t* wall_cell,
                 std::size_t r0, std::size_t r1, std::vector<std::uint32_t>& out,
                 std::uint32_t* deg_nw, std::uint32_t* deg_w, bool simd) {
  const int d = grid.dimension();
#ifdef SADR_GRAPH_AVX512
  if (simd && filter_simd_available()) {
    if (d == 1) return search_avx512<1>(grid, wall_cell, r0, r1, out, deg_nw, deg_w);
    if (d == 2) return search_avx512<2>(grid, wall_cell, r0, r1, out, deg_nw, deg_w);
    return search_avx512<3>(grid, wall_cell, r0, r1, out, deg_nw, deg_w);
  }
#else
  (void)simd;
  (void)wall_cell;
#endif
  if (d == 1) return search_scalar<1>(grid, wall, r0, r1, out, deg_nw, deg_w);
  if (d == 2) return search_scalar<2>(grid, wall, r0, r1, out, deg_nw, deg_w);
  return search_scalar<3>(grid, wall, r0, r1, out, deg_nw, deg_w);
}

}  // namespace sadr::ssa::detail
