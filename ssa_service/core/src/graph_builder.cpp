// SPDX-License-Identifier: MIT
#include "sadr/ssa/graph_builder.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>

#include "cell_grid.hpp"
#include "graph_build_detail.hpp"
#include "graph_filter.hpp"
#include "graph_search.hpp"
#include "sadr/common/periodic.hpp"

#ifdef SADR_HAVE_OPENMP
#include <omp.h>
#endif

namespace sadr::ssa {

namespace {

inline int omp_thread_id() {
#ifdef SADR_HAVE_OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

/// Threads in the current team: may be fewer than asked for (nested in another
/// parallel region, thread limits), so the row ranges follow this, not the request.
inline int omp_team_size() {
#ifdef SADR_HAVE_OPENMP
  return omp_get_num_threads();
#else
  return 1;
#endif
}

}  // namespace

void GraphBuilder::build(DiffusionGraph& g, const Model& model, const ParticleState& particles,
                         bool force_search) {
  // Usual coupled step: a candidate list exists and the rows go to several threads.
  // Validation, vertices and wrap then run on the first thread inside the filter's
  // parallel region, while the others wake up (~40 us each with passive waits).
  const int nt = valid_ && !force_search ? thread_count(particles.size()) : 1;
  bool moved_far = false;
  if (nt > 1) {
    if (prepare_and_filter(g, model, particles, nt)) return;
    moved_far = true;  // prepared, xw_ filled; a search is needed
  } else {
    detail::validate_particles(model, particles);  // before anything is written
    detail::prepare_vertices(g, particles);
    ++builds_;
    moved_far = wrap_and_check(model, particles, g);  // also fills xw_
  }
  if ((force_search || moved_far) && !search(model, particles, g)) {
    valid_ = false;
    detail::build_rows_full_stencil(g, model, particles);
    return;
  }
  filter(g, model, particles);
}

bool GraphBuilder::prepare_and_filter(DiffusionGraph& g, const Model& model, const ParticleState& p,
                                      int nt) {
  std::exception_ptr error;  // exceptions must not leave the parallel region
  bool search_needed = false;
  detail::FilterParams prm;
  detail::FilterOutputs o;
  edge_scratch_.resize(static_cast<std::size_t>(nt));
  std::vector<std::uint32_t> counts(static_cast<std::size_t>(nt), 0);
#pragma omp parallel num_threads(nt)
  {
#pragma omp master
    {
      try {
        detail::validate_particles(model, p);  // before anything is written
        detail::prepare_vertices(g, p);
        ++builds_;
        search_needed = wrap_and_check(model, p, g);
        if (!search_needed) filter_setup(g, model, p, prm, o);
      } catch (...) {
        error = std::current_exception();
      }
    }
#pragma omp barrier
    if (!error && !search_needed) filter_team(g, prm, o, counts);
  }
  if (error) std::rethrow_exception(error);
  if (search_needed) return false;
  filter_finish(g, p.size(), counts);
  return true;
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
      if (box.periodic[a]) dx = minimum_image(dx, box.length(a));
      s2 += dx * dx;
    }
    if (!(s2 < limit2)) return true;
  }
  return false;
}

bool GraphBuilder::search(const Model& model, const ParticleState& p, const DiffusionGraph& g) {
  // The cell grid is kept between searches (one per thread calling build()); the
  // OpenMP workers use the caller's through `grid` (a thread_local named inside the
  // parallel region would be each worker's own, empty one).
  thread_local detail::CellGrid grid_of_caller;
  detail::CellGrid& grid = grid_of_caller;
  const std::size_t n = p.size();
  const double cut = model.smoothing_length * (1.0 + kSkinFraction);
  grid.build(model.box, p.positions, cut);
  // A periodic axis with < 3 cells would need a per-pair minimum image; the caller
  // then builds the rows by the explicit full-stencil path.
  if (!grid.single_image()) return false;
  ++searches_;
  const std::uint8_t* wall = g.is_wall.data();
  // Wall flags in the grid's cell order, so the vectorised scan loads them contiguously.
  wall_cell_.resize(n);
  const std::uint32_t* members = grid.view().members;
  for (std::size_t m = 0; m < n; ++m) wall_cell_[m] = wall[members[m]];
  cand_start_.assign(n + 1, 0);
  cand_split_.assign(n, 0);
  // Each row searched on its own (full stencil, ~2x the distance tests of a half
  // stencil) so rows go to threads with no shared writes; each row is then
  // sorted, which makes the rows independent of the cell order and the history.
  const int nt = thread_count(n);
  cand_scratch_.resize(static_cast<std::size_t>(nt));
  std::vector<std::uint32_t> base(static_cast<std::size_t>(nt) + 1, 0);
#pragma omp parallel num_threads(nt) if (nt > 1)
  {
    const int t = omp_thread_id(), team = omp_team_size();
    const std::size_t r0 = n * t / team, r1 = n * (t + 1) / team;
    std::vector<std::uint32_t>& rows = cand_scratch_[t];
    std::uint32_t* deg_nw = cand_start_.data();  // lengths first, then offsets
    std::uint32_t* deg_w = cand_split_.data();
    detail::search_rows(grid, wall, wall_cell_.data(), r0, r1, rows, deg_nw, deg_w, simd_);
    base[t + 1] = static_cast<std::uint32_t>(rows.size());
#pragma omp barrier
#pragma omp single
    {
      for (int k = 0; k < team; ++k) base[k + 1] += base[k];
      for (int k = team; k < nt; ++k) base[k + 1] = base[k];  // no such threads
      // kCandSlack valid indices past the last row (the SIMD filter reads them).
      cand_.resize(base[nt] + detail::kCandSlack);
      std::fill(cand_.begin() + base[nt], cand_.end(), 0u);
    }  // implicit barrier
    std::uint32_t off = base[t];
    for (std::size_t i = r0; i < r1; ++i) {
      const std::uint32_t nw = deg_nw[i], w = deg_w[i];
      deg_nw[i] = off;
      deg_w[i] = off + nw;
      off += nw + w;
    }
    std::copy(rows.begin(), rows.end(), cand_.begin() + base[t]);
  }
  cand_start_[n] = base[nt];
  xref_ = xw_;
  wall_ref_ = g.is_wall;
  valid_ = true;
  return true;
}

void GraphBuilder::filter_setup(DiffusionGraph& g, const Model& model, const ParticleState& p,
                                detail::FilterParams& prm, detail::FilterOutputs& o) {
  const std::size_t n = p.size();
  const int d = model.box.dimension;
  const double h = model.smoothing_length;
  prm = detail::FilterParams{};
  prm.dim = d;
  prm.x = xw_.data();
  // Walled axes: len 0 and half +inf, so the branch-free minimum image is the
  // identity there (dx - 0 * 0 == dx).
  for (int a = 0; a < 3; ++a) {
    const bool per = a < d && model.box.periodic[a];
    prm.len[a] = per ? model.box.length(a) : 0.0;
    prm.half[a] = per ? 0.5 * prm.len[a] : std::numeric_limits<double>::infinity();
  }
  prm.h2 = h * h;
  prm.eps_h2 = model.regularization * h * h;
  prm.inv_h = 1.0 / h;
  prm.f0 = lucy_f(0.0, h, d);  // F(r) = f0 (1 - r/h)^2
  prm.symmetric = model.convention == JumpConvention::kSymmetric;
  prm.m = p.masses.data();
  prm.rho = p.densities.data();
  prm.vol = g.volume.data();
  prm.cand_start = cand_start_.data();
  prm.cand_split = cand_split_.data();
  prm.cand = cand_.data();
  o = detail::FilterOutputs{g.row_start.data(), g.split.data(), g.sum_nowall.data(),
                            g.sum_all.data(), g.wall_distance.data()};
  // Upper bound first (no reallocation once the candidate count stopped growing;
  // shrinking afterwards does not free), then trimmed to the edges kept.
  if (g.edges.size() < cand_start_[n] + detail::kFilterSlack) {
    g.edges.resize(cand_start_[n] + detail::kFilterSlack);
  }
}

void GraphBuilder::filter(DiffusionGraph& g, const Model& model, const ParticleState& p) {
  const std::size_t n = p.size();
  detail::FilterParams prm;
  detail::FilterOutputs o;
  filter_setup(g, model, p, prm, o);
  const int nt = thread_count(n);
  std::vector<std::uint32_t> counts(static_cast<std::size_t>(nt), 0);  // 0 past the team
  if (nt == 1) {
    counts[0] = detail::filter_rows(prm, 0, n, g.edges.data(), o, simd_);
  } else {
    edge_scratch_.resize(static_cast<std::size_t>(nt));
#pragma omp parallel num_threads(nt)
    filter_team(g, prm, o, counts);
  }
  filter_finish(g, n, counts);
}

void GraphBuilder::filter_team(DiffusionGraph& g, const detail::FilterParams& prm,
                               const detail::FilterOutputs& o, std::vector<std::uint32_t>& counts) {
  // Rows split into ranges of about equal candidate counts, one per thread of the
  // team. Range 0 writes its edges in place; the others into scratch, copied behind
  // it once every count is known, by all threads (equal slices of the edges to
  // move: one thread copying 1.6 MB at 1e4 particles in 2D was a serial tail of
  // ~0.1 ms). Each row is computed the same way whatever the split, so the graph
  // does not depend on the thread count.
  const int t = omp_thread_id(), team = omp_team_size();
  const std::size_t r0 = row_split(t, team), r1 = row_split(t + 1, team);
  DiffusionGraph::Edge* dst = g.edges.data();
  if (t > 0) {
    std::vector<DiffusionGraph::Edge>& s = edge_scratch_[t];
    const std::size_t need = cand_start_[r1] - cand_start_[r0] + detail::kFilterSlack;
    if (s.size() < need) s.resize(need);
    dst = s.data();
  }
  counts[t] = detail::filter_rows(prm, r0, r1, dst, o, simd_);
#pragma omp barrier
  // Destination offsets of the ranges; edges [counts[0], total) are moved in
  // `team` slices, each thread copying the parts of the ranges in its slice.
  std::uint32_t base[kMaxCopyRanges + 1] = {0};
  const int ranges = std::min(team, kMaxCopyRanges);
  for (int k = 0; k < ranges; ++k) base[k + 1] = base[k] + counts[k];
  const std::uint32_t total = base[ranges];
  const std::uint32_t lo =
      counts[0] + static_cast<std::uint32_t>(std::uint64_t{total - counts[0]} * t / team);
  const std::uint32_t hi =
      counts[0] + static_cast<std::uint32_t>(std::uint64_t{total - counts[0]} * (t + 1) / team);
  for (int k = 1; k < ranges; ++k) {
    const std::uint32_t b = std::max(lo, base[k]), e = std::min(hi, base[k + 1]);
    if (b < e) {
      const DiffusionGraph::Edge* src = edge_scratch_[k].data() + (b - base[k]);
      std::copy(src, src + (e - b), g.edges.data() + b);
    }
  }
  if (t > 0) {
    for (std::size_t i = r0; i < r1; ++i) {
      g.row_start[i] += base[t];
      g.split[i] += base[t];
    }
  }
}

void GraphBuilder::filter_finish(DiffusionGraph& g, std::size_t n,
                                 const std::vector<std::uint32_t>& counts) {
  std::uint32_t out = 0;
  for (const std::uint32_t c : counts) out += c;
  g.row_start[n] = out;
  g.edges.resize(out);
}

int GraphBuilder::threads() const {
#ifdef SADR_HAVE_OPENMP
  return threads_ > 0 ? threads_ : omp_get_max_threads();
#else
  return 1;
#endif
}

int GraphBuilder::thread_count(std::size_t rows) const {
  // Below ~1000 rows per thread the fork/join costs more than the rows.
  const std::size_t by_size = rows / kMinRowsPerThread;
  const int most = std::min(threads(), kMaxCopyRanges);
  return static_cast<int>(std::clamp<std::size_t>(by_size, 1, static_cast<std::size_t>(most)));
}

std::size_t GraphBuilder::row_split(int t, int nt) const {
  const std::size_t n = cand_start_.size() - 1;
  if (t <= 0) return 0;
  if (t >= nt) return n;
  const std::uint64_t target = static_cast<std::uint64_t>(cand_start_[n]) * t / nt;
  return static_cast<std::size_t>(
      std::lower_bound(cand_start_.begin(), cand_start_.end() - 1, target) - cand_start_.begin());
}

}  // namespace sadr::ssa
