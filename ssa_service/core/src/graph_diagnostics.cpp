// SPDX-License-Identifier: MIT
#include "sadr/ssa/graph_diagnostics.hpp"

#include <algorithm>
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/connected_components.hpp>
#include <cstdio>
#include <limits>

namespace sadr::ssa {
namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

}  // namespace

GraphDiagnostics diagnose_graph(const DiffusionGraph& graph, const Model& model) {
  GraphDiagnostics d;
  const std::size_t n = graph.size();
  d.voxels = n;
  d.edges = graph.edge_count();
  if (n == 0) return d;
  // Undirected view for Boost: one edge per i < j pair (the rows hold both directions).
  using Undirected = boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS>;
  Undirected u(n);
  d.min_degree = std::numeric_limits<std::size_t>::max();
  d.min_weight = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t begin = graph.row_start[i];
    const std::uint32_t end = graph.row_start[i + 1];
    const std::size_t degree = end - begin;
    d.min_degree = std::min(d.min_degree, degree);
    d.max_degree = std::max(d.max_degree, degree);
    if (graph.is_wall[i]) ++d.wall_voxels;
    bool fluid_neighbour = false;
    for (std::uint32_t k = begin; k < end; ++k) {
      const auto& e = graph.edges[k];
      // Edges are packed to 12 bytes (4-byte aligned): copy the weight before std::min/max
      // bind a reference to it (a misaligned double reference is undefined behaviour).
      const double w = e.weight;
      d.min_weight = std::min(d.min_weight, w);
      d.max_weight = std::max(d.max_weight, w);
      if (!graph.is_wall[e.target]) fluid_neighbour = true;
      if (i < e.target) boost::add_edge(i, e.target, u);
    }
    if (!graph.is_wall[i] && !fluid_neighbour) {
      if (!d.isolated_example) d.isolated_example = static_cast<std::uint32_t>(i);
      ++d.isolated;
    }
  }
  d.mean_degree = static_cast<double>(d.edges) / static_cast<double>(n);
  if (d.edges == 0) d.min_weight = 0;
  std::vector<std::size_t> component(n);
  d.components = static_cast<std::size_t>(boost::connected_components(u, component.data()));
  std::vector<std::size_t> sizes(d.components, 0);
  for (std::size_t c : component) ++sizes[c];
  d.largest_component = *std::max_element(sizes.begin(), sizes.end());
  // Rates kappa_s D_ij: the extremes are products of the extreme kappa and D.
  for (const Species& entry : model.species) {
    const model::Species& s = entry.def;
    if (s.diffusivity <= 0 || d.edges == 0) continue;
    if (d.min_rate_species.empty() || s.diffusivity * d.min_weight < d.min_rate) {
      d.min_rate = s.diffusivity * d.min_weight;
      d.min_rate_species = s.name;
    }
    if (d.max_rate_species.empty() || s.diffusivity * d.max_weight > d.max_rate) {
      d.max_rate = s.diffusivity * d.max_weight;
      d.max_rate_species = s.name;
    }
  }
  return d;
}

std::vector<std::string> GraphDiagnostics::lines() const {
  std::vector<std::string> out;
  out.push_back("SSA graph: " + std::to_string(voxels) + " voxels (" + std::to_string(wall_voxels) +
                " wall), " + std::to_string(edges) + " directed edges, degree " +
                std::to_string(min_degree) + " / " + number(mean_degree) + " / " +
                std::to_string(max_degree) + " (min/mean/max), " + std::to_string(components) +
                " connected component" + (components == 1 ? "" : "s") + " (largest " +
                std::to_string(largest_component) + "), " + std::to_string(isolated) + " isolated");
  if (edges > 0) {
    std::string rates =
        "SSA graph: D_ij in [" + number(min_weight) + ", " + number(max_weight) + "] 1/L^2";
    if (!min_rate_species.empty()) {
      rates += ", jump rates kappa D_ij in [" + number(min_rate) + " (" + min_rate_species + "), " +
               number(max_rate) + " (" + max_rate_species + ")] 1/T";
    }
    out.push_back(rates);
  }
  return out;
}

std::string GraphDiagnostics::isolated_warning() const {
  if (isolated == 0) return {};
  return std::to_string(isolated) + " of " + std::to_string(voxels - wall_voxels) +
         " fluid voxels of the SSA graph have no fluid neighbour within h (e.g. particle " +
         std::to_string(*isolated_example) +
         "): molecules there never diffuse through the fluid; raise fluid.h_over_dx or "
         "smoothing_length";
}

}  // namespace sadr::ssa
