// SPDX-License-Identifier: MIT
#include "sadr/ssa/diffusion_graph.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "cell_grid.hpp"
#include "sadr/common/status.hpp"

namespace sadr::ssa {

double lucy_f(double r, double h, int dimension) {
  const double q = r / h;
  if (q >= 1.0) return 0.0;
  double alpha = 0;
  switch (dimension) {
    case 1:
      alpha = 5.0 / (4.0 * h);
      break;
    case 2:
      alpha = 5.0 / (std::numbers::pi * h * h);
      break;
    default:
      alpha = 105.0 / (16.0 * std::numbers::pi * h * h * h);
      break;
  }
  return 12.0 * alpha * (1.0 - q) * (1.0 - q) / (h * h);
}

namespace {

void validate_particles(const Model& model, const ParticleState& p) {
  p.validate();
  if (p.dimension != model.box.dimension) {
    throw InvalidArgument("particle state: dimension = " + std::to_string(p.dimension) +
                              " but model.box.dimension = " + std::to_string(model.box.dimension),
                          {{"field", "dimension"}, {"value", std::to_string(p.dimension)}});
  }
  if (p.size() >= std::numeric_limits<std::uint32_t>::max()) {
    throw InvalidArgument("particle state: " + std::to_string(p.size()) +
                          " particles (allowed: < 2^32 - 1)");
  }
  const Box& b = model.box;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (int a = 0; a < b.dimension; ++a) {
      const double x = p.positions[3 * i + a];
      if (!b.periodic[a] && (x < b.lo[a] || x > b.hi[a])) {
        throw InvalidArgument("particle " + std::to_string(i) + ": position[" + std::to_string(a) +
                                  "] = " + format_value(x) + " is outside the walled box axis [" +
                                  format_value(b.lo[a]) + ", " + format_value(b.hi[a]) + "]",
                              {{"field", "positions"}, {"value", format_value(x)}});
      }
    }
  }
  for (std::size_t r = 0; r < model.reactions.size(); ++r) {
    for (std::uint32_t v : model.reactions[r].voxels) {
      if (v >= p.size()) {
        throw InvalidArgument("reactions[" + std::to_string(r) + "].voxels contains " +
                              std::to_string(v) + " (allowed: 0.." + std::to_string(p.size() - 1) +
                              ")");
      }
    }
  }
}

}  // namespace

namespace {

/// The rows of the graph from the cell grid: for each particle i, the pairs
/// within h in cell order, weights computed on the fly, non-wall targets
/// first (then the wall targets, kept aside in `wall_edges`).
template <int D>
void fill_rows(DiffusionGraph& g, const detail::CellGrid& grid, const Model& model,
               const ParticleState& particles, std::vector<DiffusionGraph::Edge>& wall_edges) {
  const std::size_t n = particles.size();
  const double h = model.smoothing_length;
  const double eps_h2 = model.regularization * h * h;
  const double inv_h = 1.0 / h;
  // F(r) = 12 alpha_d (1 - q)^2 / h^2 (lucy_f), with the constant hoisted.
  const double f0 = lucy_f(0.0, h, D);
  const bool symmetric = model.convention == JumpConvention::kSymmetric;
  const double* m = particles.masses.data();
  const double* rho = particles.densities.data();
  const double* vol = g.volume.data();
  const std::uint8_t* wall = g.is_wall.data();
  const bool any_wall =
      std::any_of(g.is_wall.begin(), g.is_wall.end(), [](std::uint8_t w) { return w != 0; });
  g.edges.clear();
  for (std::size_t i = 0; i < n; ++i) {
    g.row_start[i] = static_cast<std::uint32_t>(g.edges.size());
    wall_edges.clear();
    double sum_nowall = 0, sum_wall = 0, wall_r2 = std::numeric_limits<double>::infinity();
    const double mi = m[i], rhoi = rho[i];
    grid.for_each_neighbor<D>(static_cast<std::uint32_t>(i), [&](std::uint32_t j, double r2) {
      const double r = std::sqrt(r2);
      const double one_q = 1.0 - r * inv_h;
      const double reg_f = (r2 / (r2 + eps_h2)) * (f0 * one_q * one_q);
      // Volume-consistent: D_ij = 2 V_j F_ij reg, so D_ij V_i = D_ji V_j.
      // drawert2019 eq 28: D_ij = 2 m_i m_j/(m_i+m_j) (rho_i+rho_j)/(rho_i rho_j) reg F_ij.
      const double w =
          symmetric ? 2.0 * (mi * m[j] / (mi + m[j])) * ((rhoi + rho[j]) / (rhoi * rho[j])) * reg_f
                    : 2.0 * vol[j] * reg_f;
      if (any_wall && wall[j]) {
        if (r2 < wall_r2) wall_r2 = r2;
        if (!(w > 0)) return;  // coincident particles (reg = 0) carry no edge
        wall_edges.push_back(DiffusionGraph::Edge{w, j});
        sum_wall += w;
      } else {
        if (!(w > 0)) return;
        g.edges.push_back(DiffusionGraph::Edge{w, j});
        sum_nowall += w;
      }
    });
    g.split[i] = static_cast<std::uint32_t>(g.edges.size());
    g.edges.insert(g.edges.end(), wall_edges.begin(), wall_edges.end());
    g.sum_nowall[i] = sum_nowall;
    g.sum_all[i] = sum_nowall + sum_wall;
    g.wall_distance[i] = std::sqrt(wall_r2);
  }
  g.row_start[n] = static_cast<std::uint32_t>(g.edges.size());
}

/// One undirected edge found by the half-stencil search, both directed weights.
struct PairEdge {
  std::uint32_t i, j;
  double w_ij, w_ji;
};

/// Scratch reused between builds (one per thread).
struct PairScratch {
  std::vector<PairEdge> pairs;
  std::vector<std::uint32_t> cursor_nowall, cursor_wall;
  std::vector<double> wall_r2;
};

/// The graph from the half-stencil pair search: each pair's kernel factor
/// F reg (one sqrt, one division) is computed once and written into both rows;
/// rows are laid out by counting (non-wall targets first).
template <int D>
void fill_rows_pairs(DiffusionGraph& g, const detail::CellGrid& grid, const Model& model,
                     const ParticleState& particles, PairScratch& sc) {
  const std::size_t n = particles.size();
  const double h = model.smoothing_length;
  const double eps_h2 = model.regularization * h * h;
  const double inv_h = 1.0 / h;
  const double f0 = lucy_f(0.0, h, D);  // F(r) = f0 (1 - r/h)^2
  const bool symmetric = model.convention == JumpConvention::kSymmetric;
  const double* m = particles.masses.data();
  const double* rho = particles.densities.data();
  const double* vol = g.volume.data();
  const std::uint8_t* wall = g.is_wall.data();
  const bool any_wall =
      std::any_of(g.is_wall.begin(), g.is_wall.end(), [](std::uint8_t w) { return w != 0; });
  sc.pairs.clear();
  sc.cursor_nowall.assign(n + 1, 0);  // degrees first, then write cursors
  sc.cursor_wall.assign(n, 0);
  std::uint32_t* deg_nw = sc.cursor_nowall.data();
  std::uint32_t* deg_w = sc.cursor_wall.data();
  if (any_wall) sc.wall_r2.assign(n, std::numeric_limits<double>::infinity());
  grid.for_each_pair<D>([&](std::uint32_t i, std::uint32_t j, double r2) {
    if (any_wall) {
      if (wall[j] && r2 < sc.wall_r2[i]) sc.wall_r2[i] = r2;
      if (wall[i] && r2 < sc.wall_r2[j]) sc.wall_r2[j] = r2;
    }
    const double r = std::sqrt(r2);
    const double one_q = 1.0 - r * inv_h;
    const double reg_f = (r2 / (r2 + eps_h2)) * (f0 * one_q * one_q);
    double w_ij = 0, w_ji = 0;
    if (symmetric) {
      // drawert2019 eq 28: D_ij = 2 m_i m_j/(m_i+m_j) (rho_i+rho_j)/(rho_i rho_j) reg F_ij.
      w_ij = w_ji =
          2.0 * (m[i] * m[j] / (m[i] + m[j])) * ((rho[i] + rho[j]) / (rho[i] * rho[j])) * reg_f;
    } else {
      // Volume-consistent: D_ij = 2 V_j F_ij reg, so D_ij V_i = D_ji V_j.
      w_ij = 2.0 * vol[j] * reg_f;
      w_ji = 2.0 * vol[i] * reg_f;
    }
    if (!(w_ij > 0 && w_ji > 0)) return;  // coincident particles (reg = 0) carry no edge
    sc.pairs.push_back(PairEdge{i, j, w_ij, w_ji});
    ++(any_wall && wall[j] ? deg_w[i] : deg_nw[i]);
    ++(any_wall && wall[i] ? deg_w[j] : deg_nw[j]);
  });
  // Row layout: [row_start, split) non-wall targets, [split, next row) walls.
  std::uint32_t out = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t nw = deg_nw[i], w = deg_w[i];
    g.row_start[i] = out;
    g.split[i] = out + nw;
    deg_nw[i] = out;
    deg_w[i] = out + nw;
    out += nw + w;
  }
  g.row_start[n] = out;
  g.edges.resize(out);
  DiffusionGraph::Edge* e = g.edges.data();
  std::fill(g.sum_all.begin(), g.sum_all.end(), 0.0);
  std::fill(g.sum_nowall.begin(), g.sum_nowall.end(), 0.0);
  double* sum_all = g.sum_all.data();
  double* sum_nowall = g.sum_nowall.data();
  for (const PairEdge& p : sc.pairs) {
    const bool wi = any_wall && wall[p.i], wj = any_wall && wall[p.j];
    e[(wj ? deg_w[p.i] : deg_nw[p.i])++] = DiffusionGraph::Edge{p.w_ij, p.j};
    e[(wi ? deg_w[p.j] : deg_nw[p.j])++] = DiffusionGraph::Edge{p.w_ji, p.i};
    sum_all[p.i] += p.w_ij;
    sum_all[p.j] += p.w_ji;
    if (!wj) sum_nowall[p.i] += p.w_ij;
    if (!wi) sum_nowall[p.j] += p.w_ji;
  }
  for (std::size_t i = 0; i < n; ++i) {
    g.wall_distance[i] =
        any_wall ? std::sqrt(sc.wall_r2[i]) : std::numeric_limits<double>::infinity();
  }
}

}  // namespace

DiffusionGraph DiffusionGraph::build(const Model& model, const ParticleState& particles) {
  DiffusionGraph g;
  build_into(g, model, particles);
  return g;
}

void DiffusionGraph::build_into(DiffusionGraph& g, const Model& model,
                                const ParticleState& particles) {
  validate_particles(model, particles);
  // Cell grid and scratch reused between builds (one per thread).
  thread_local detail::CellGrid grid;
  thread_local std::vector<Edge> wall_edges;
  const std::size_t n = particles.size();
  const int d = model.box.dimension;
  grid.build(model.box, particles.positions, model.smoothing_length);
  g.dimension = d;
  g.volume.resize(n);
  g.is_wall.resize(n);
  g.kind.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    g.volume[i] = particles.masses[i] / particles.densities[i];
    g.kind[i] = particles.kind(i);
    g.is_wall[i] = g.kind[i] == ParticleKind::kWall ? 1 : 0;
  }
  g.row_start.resize(n + 1);
  g.split.resize(n);
  g.sum_all.resize(n);
  g.sum_nowall.resize(n);
  g.wall_distance.resize(n);
  if (grid.half_stencil_ok()) {
    thread_local PairScratch scratch;
    if (d == 1) fill_rows_pairs<1>(g, grid, model, particles, scratch);
    if (d == 2) fill_rows_pairs<2>(g, grid, model, particles, scratch);
    if (d == 3) fill_rows_pairs<3>(g, grid, model, particles, scratch);
    return;
  }
  if (d == 1) fill_rows<1>(g, grid, model, particles, wall_edges);
  if (d == 2) fill_rows<2>(g, grid, model, particles, wall_edges);
  if (d == 3) fill_rows<3>(g, grid, model, particles, wall_edges);
}

}  // namespace sadr::ssa
