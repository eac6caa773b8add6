// SPDX-License-Identifier: MIT
#include "sadr/ssa/diffusion_graph.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "cell_grid.hpp"
#include "graph_build_detail.hpp"
#include "sadr/common/status.hpp"
#include "sadr/ssa/graph_builder.hpp"

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

namespace detail {

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
  // Every weight is at most 4 V_max F(0) (both conventions), a row sum N times that:
  // a volume beyond this bound would make a weight or a row sum overflow to inf and
  // the rates NaN (a density of 1e-310 is > 0 and finite; found by fuzz_ssa_requests).
  const double volume_limit =
      std::numeric_limits<double>::max() /
      (4.0 * lucy_f(0.0, model.smoothing_length, b.dimension) * static_cast<double>(p.size()));
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (const double v = p.volume(i); !(v <= volume_limit)) {
      throw InvalidArgument("particle " + std::to_string(i) +
                                ": volume mass / density = " + format_value(p.masses[i]) + " / " +
                                format_value(p.densities[i]) + " = " + format_value(v) +
                                " (allowed: <= " + format_value(volume_limit) +
                                ", so that the jump rates stay finite)",
                            {{"field", "densities"}, {"value", format_value(p.densities[i])}});
    }
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

}  // namespace detail

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

}  // namespace

DiffusionGraph DiffusionGraph::build(const Model& model, const ParticleState& particles) {
  DiffusionGraph g;
  build_into(g, model, particles);
  return g;
}

void DiffusionGraph::build_into(DiffusionGraph& g, const Model& model,
                                const ParticleState& particles) {
  // The same code path as the solver's per-step rebuild, with a fresh search, so
  // build() and NsmSolver::graph() agree edge for edge.
  thread_local GraphBuilder builder;
  builder.build(g, model, particles, /*force_search=*/true);
}

namespace detail {

void prepare_vertices(DiffusionGraph& g, const ParticleState& particles) {
  const std::size_t n = particles.size();
  g.dimension = particles.dimension;
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
}

void build_rows_full_stencil(DiffusionGraph& g, const Model& model,
                             const ParticleState& particles) {
  thread_local CellGrid grid;
  thread_local std::vector<DiffusionGraph::Edge> wall_edges;
  grid.build(model.box, particles.positions, model.smoothing_length);
  const int d = model.box.dimension;
  if (d == 1) fill_rows<1>(g, grid, model, particles, wall_edges);
  if (d == 2) fill_rows<2>(g, grid, model, particles, wall_edges);
  if (d == 3) fill_rows<3>(g, grid, model, particles, wall_edges);
}

}  // namespace detail

}  // namespace sadr::ssa
