// SPDX-License-Identifier: MIT
#include "sadr/ssa/graph_builder.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

#include "cell_grid.hpp"
#include "graph_build_detail.hpp"

namespace sadr::ssa {

namespace {

/// Wraps a coordinate of a periodic axis into [lo, hi) (the formula of neighbor_list.cpp).
inline double wrap_into(double v, double lo, double hi) {
  const double len = hi - lo;
  v = lo + (v - lo) - len * std::floor((v - lo) / len);
  return v >= hi ? lo : v;
}

/// Minimum-image difference on a periodic axis of length len (coordinates wrapped,
/// |true difference| < len / 2). Odd in dx bit for bit, so r_ij == r_ji exactly
/// (filter() uses a branch-free form with the same results).
inline double min_image(double dx, double len, double half) {
  if (dx > half) return dx - len;
  if (dx < -half) return dx + len;
  return dx;
}

}  // namespace

void GraphBuilder::build(DiffusionGraph& g, const Model& model, const ParticleState& particles,
                         bool force_search) {
  detail::validate_particles(model, particles);  // before anything is written
  detail::prepare_vertices(g, particles);
  ++builds_;
  const bool moved_far = wrap_and_check(model, particles, g);  // also fills xw_
  if ((force_search || moved_far) && !search(model, particles, g)) {
    valid_ = false;
    detail::build_rows_full_stencil(g, model, particles);
    return;
  }
  switch (model.box.dimension) {
    case 1:
      filter<1>(g, model, particles);
      break;
    case 2:
      filter<2>(g, model, particles);
      break;
    default:
      filter<3>(g, model, particles);
      break;
  }
}

bool GraphBuilder::wrap_and_check(const Model& model, const ParticleState& p,
                                  const DiffusionGraph& g) {
  const Box& box = model.box;
  const int d = box.dimension;
  const std::size_t n = p.size();
  xw_.resize(static_cast<std::size_t>(d) * n);
  for (std::size_t i = 0; i < n; ++i) {
    for (int a = 0; a < d; ++a) {
      const double v = p.positions[3 * i + a];
      // Coordinates already inside stay bitwise as given (the floor/division of
      // wrap_into() was ~120 instructions per voxel, callgrind scenario d).
      const bool inside = v >= box.lo[a] && v < box.hi[a];
      xw_[d * i + a] = box.periodic[a] && !inside ? wrap_into(v, box.lo[a], box.hi[a]) : v;
    }
  }
  if (!valid_ || xref_.size() != xw_.size() || wall_ref_ != g.is_wall) return true;
  // Largest displacement since the search (minimum image on periodic axes).
  const double skin = kSkinFraction * model.smoothing_length;
  // 0.49 instead of 0.5: a margin far above the round-off of the distances.
  const double limit2 = (0.49 * skin) * (0.49 * skin);
  for (std::size_t i = 0; i < n; ++i) {
    double s2 = 0;
    for (int a = 0; a < d; ++a) {
      double dx = xw_[d * i + a] - xref_[d * i + a];
      if (box.periodic[a]) dx = min_image(dx, box.length(a), 0.5 * box.length(a));
      s2 += dx * dx;
    }
    if (!(s2 < limit2)) return true;
  }
  return false;
}

bool GraphBuilder::search(const Model& model, const ParticleState& p, const DiffusionGraph& g) {
  // Scratch kept between searches (one per thread): the cell grid and the pair list.
  thread_local detail::CellGrid grid;
  thread_local std::vector<std::uint32_t> pairs, by_target, cursor;
  const std::size_t n = p.size();
  const double cut = model.smoothing_length * (1.0 + kSkinFraction);
  grid.build(model.box, p.positions, cut);
  if (!grid.half_stencil_ok()) return false;
  ++searches_;
  const std::uint8_t* wall = g.is_wall.data();
  cand_start_.assign(n + 1, 0);
  cand_split_.assign(n, 0);
  std::uint32_t* deg_nw = cand_start_.data();  // degrees first, then offsets
  std::uint32_t* deg_w = cand_split_.data();
  pairs.clear();
  auto collect = [&](std::uint32_t i, std::uint32_t j, double) {
    pairs.push_back(i);
    pairs.push_back(j);
    ++(wall[j] ? deg_w[i] : deg_nw[i]);
    ++(wall[i] ? deg_w[j] : deg_nw[j]);
  };
  const int d = model.box.dimension;
  if (d == 1) grid.for_each_pair<1>(collect);
  if (d == 2) grid.for_each_pair<2>(collect);
  if (d == 3) grid.for_each_pair<3>(collect);
  // Row layout: [start, split) non-wall targets, [split, next start) wall targets.
  std::uint32_t out = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t nw = deg_nw[i], w = deg_w[i];
    deg_nw[i] = out;
    deg_w[i] = out + nw;
    out += nw + w;
  }
  cand_start_[n] = out;
  // Sorted rows without a comparison sort (two counting passes, O(pairs)):
  // bucket the sources by target (a vertex has as many in- as out-candidates,
  // so the buckets are the rows), then scan the targets in ascending order and
  // append each to the rows of its sources.
  by_target.resize(out);
  cursor.assign(cand_start_.begin(), cand_start_.end() - 1);
  for (std::size_t k = 0; k < pairs.size(); k += 2) {
    const std::uint32_t i = pairs[k], j = pairs[k + 1];
    by_target[cursor[j]++] = i;
    by_target[cursor[i]++] = j;
  }
  cand_.resize(out);
  std::copy(cand_start_.begin(), cand_start_.end() - 1, cursor.begin());
  std::vector<std::uint32_t>& wcur = pairs;  // reused as the wall-part cursors
  wcur.assign(cand_split_.begin(), cand_split_.end());
  for (std::uint32_t t = 0; t < n; ++t) {
    for (std::uint32_t k = cand_start_[t]; k < cand_start_[t + 1]; ++k) {
      const std::uint32_t s = by_target[k];
      cand_[wall[t] ? wcur[s]++ : cursor[s]++] = t;
    }
  }
  xref_ = xw_;
  wall_ref_ = g.is_wall;
  valid_ = true;
  return true;
}

template <int D>
void GraphBuilder::filter(DiffusionGraph& g, const Model& model, const ParticleState& p) const {
  const std::size_t n = p.size();
  const double h = model.smoothing_length;
  const double h2 = h * h;
  const double eps_h2 = model.regularization * h * h;
  const double inv_h = 1.0 / h;
  const double f0 = lucy_f(0.0, h, D);  // F(r) = f0 (1 - r/h)^2
  const bool symmetric = model.convention == JumpConvention::kSymmetric;
  const double* m = p.masses.data();
  const double* rho = p.densities.data();
  const double* vol = g.volume.data();
  const double* x = xw_.data();
  // Walled axes: len 0 and half +inf, so the branch-free minimum image below is
  // the identity there (dx - 0 * 0 == dx).
  double len[3] = {0, 0, 0}, half[3];
  for (int a = 0; a < 3; ++a) half[a] = std::numeric_limits<double>::infinity();
  for (int a = 0; a < D; ++a) {
    if (!model.box.periodic[a]) continue;
    len[a] = model.box.length(a);
    half[a] = 0.5 * len[a];
  }
  const std::uint32_t* cs = cand_start_.data();
  const std::uint32_t* csplit = cand_split_.data();
  const std::uint32_t* cand = cand_.data();
  // Upper bound first (no reallocation once the candidate count stopped growing;
  // shrinking afterwards does not free), then trimmed to the edges kept.
  if (g.edges.size() < cand_.size()) g.edges.resize(cand_.size());
  DiffusionGraph::Edge* e = g.edges.data();
  // Per-row scratch: r2 and F reg of every candidate, computed in branch-free loops
  // the compiler vectorises (sqrt and division two at a time; -fno-math-errno),
  // then compressed to the edges with r < h. Computing each pair once (j > i, the
  // result stored in the reverse slot for row j) was slower: 583-593 vs 395-400
  // ns/voxel per rebuild in interleaved runs of scenario d; the scattered stores
  // cost more than the sqrt and division they save.
  thread_local std::vector<double> r2buf, fbuf;
  std::uint32_t max_row = 0;
  for (std::size_t i = 0; i < n; ++i) max_row = std::max(max_row, cs[i + 1] - cs[i]);
  if (r2buf.size() < max_row) r2buf.resize(max_row), fbuf.resize(max_row);
  double* r2s = r2buf.data();
  double* fs = fbuf.data();
  std::uint32_t out = 0;
  for (std::size_t i = 0; i < n; ++i) {
    double xi[3] = {0, 0, 0};
    for (int a = 0; a < D; ++a) xi[a] = x[D * i + a];
    const std::uint32_t kb = cs[i], ks = csplit[i], ke = cs[i + 1], len_row = ke - kb;
    const std::uint32_t* row = cand + kb;
    for (std::uint32_t k = 0; k < len_row; ++k) {
      const double* xj = x + static_cast<std::size_t>(D) * row[k];
      double r2 = 0;
      for (int a = 0; a < D; ++a) {
        // Branch-free minimum image: dx - len, dx or dx + len, exactly as min_image().
        double dx = xi[a] - xj[a];
        dx -= len[a] *
              static_cast<double>(static_cast<int>(dx > half[a]) - static_cast<int>(dx < -half[a]));
        r2 += dx * dx;
      }
      r2s[k] = r2;
    }
    for (std::uint32_t k = 0; k < len_row; ++k) {
      const double r2 = r2s[k];
      const double one_q = 1.0 - std::sqrt(r2) * inv_h;  // garbage beyond h: dropped below
      fs[k] = (r2 / (r2 + eps_h2)) * (f0 * one_q * one_q);
    }
    const double mi = m[i], rhoi = rho[i], vi = vol[i];
    double wall_r2 = std::numeric_limits<double>::infinity();
    // Keeps the candidates of [k0, k1) with r < h and a positive weight; returns
    // their weight sum (row order). Two calls: non-wall part, then wall part.
    auto keep = [&](std::uint32_t k0, std::uint32_t k1, auto to_wall) {
      double sum = 0;
      for (std::uint32_t k = k0; k < k1; ++k) {
        const double r2 = r2s[k];
        if (!(r2 < h2)) continue;
        if constexpr (decltype(to_wall)::value) wall_r2 = std::min(wall_r2, r2);
        const std::uint32_t j = row[k];
        const double reg_f = fs[k];
        double w_ij = 0, w_ji = 0;
        if (symmetric) {
          // drawert2019 eq 28: D_ij = 2 m_i m_j/(m_i+m_j) (rho_i+rho_j)/(rho_i rho_j) reg F_ij.
          w_ij = w_ji =
              2.0 * (mi * m[j] / (mi + m[j])) * ((rhoi + rho[j]) / (rhoi * rho[j])) * reg_f;
        } else {
          // Volume-consistent: D_ij = 2 V_j F_ij reg, so D_ij V_i = D_ji V_j.
          w_ij = 2.0 * vol[j] * reg_f;
          w_ji = 2.0 * vi * reg_f;
        }
        if (!(w_ij > 0 && w_ji > 0)) continue;  // coincident particles (reg = 0): no edge
        e[out++] = DiffusionGraph::Edge{w_ij, j};
        sum += w_ij;
      }
      return sum;
    };
    g.row_start[i] = out;
    const double sum_nowall = keep(0, ks - kb, std::false_type{});
    g.split[i] = out;
    const double sum_wall = keep(ks - kb, len_row, std::true_type{});
    g.sum_nowall[i] = sum_nowall;
    g.sum_all[i] = sum_nowall + sum_wall;
    g.wall_distance[i] = std::sqrt(wall_r2);
  }
  g.row_start[n] = out;
  g.edges.resize(out);
}

}  // namespace sadr::ssa
