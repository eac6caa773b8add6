// SPDX-License-Identifier: MIT
#include "sadr/ssa/diffusion_graph.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "sadr/common/status.hpp"
#include "sadr/ssa/neighbor_list.hpp"

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

DiffusionGraph DiffusionGraph::build(const Model& model, const ParticleState& particles) {
  validate_particles(model, particles);
  const std::size_t n = particles.size();
  const double h = model.smoothing_length;
  const double eps_h2 = model.regularization * h * h;
  const int d = model.box.dimension;
  const NeighborList nl = build_neighbor_list(model.box, particles.positions, h);

  DiffusionGraph g;
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
  g.edges.resize(nl.col.size());
  g.sum_all.assign(n, 0.0);
  g.sum_nowall.assign(n, 0.0);
  g.wall_distance.assign(n, std::numeric_limits<double>::infinity());
  const bool symmetric = model.convention == JumpConvention::kSymmetric;
  const double* m = particles.masses.data();
  const double* rho = particles.densities.data();
  std::uint32_t out = 0;
  for (std::size_t i = 0; i < n; ++i) {
    g.row_start[i] = out;
    // Two passes over the row: non-wall targets first, then wall targets.
    for (int pass = 0; pass < 2; ++pass) {
      if (pass == 1) g.split[i] = out;
      for (std::uint32_t k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k) {
        const std::uint32_t j = nl.col[k];
        if (g.is_wall[j] != pass) continue;
        const double r2 = nl.r2[k];
        const double r = std::sqrt(r2);
        if (pass == 1 && r < g.wall_distance[i]) g.wall_distance[i] = r;
        const double reg = r2 / (r2 + eps_h2);
        const double f = lucy_f(r, h, d);
        double w = 0;
        if (symmetric) {
          // drawert2019 eq 28: D_ij = 2 m_i m_j/(m_i+m_j) (rho_i+rho_j)/(rho_i rho_j) reg F_ij.
          w = 2.0 * (m[i] * m[j] / (m[i] + m[j])) * ((rho[i] + rho[j]) / (rho[i] * rho[j])) * reg *
              f;
        } else {
          // Volume-consistent: D_ij = 2 V_j F_ij reg, so D_ij V_i = D_ji V_j.
          w = 2.0 * g.volume[j] * reg * f;
        }
        if (!(w > 0)) continue;  // coincident particles (reg = 0) carry no edge
        g.edges[out] = Edge{w, j};
        ++out;
        g.sum_all[i] += w;
        if (pass == 0) g.sum_nowall[i] += w;
      }
    }
  }
  g.row_start[n] = out;
  g.edges.resize(out);
  return g;
}

}  // namespace sadr::ssa
