// SPDX-License-Identifier: MIT
#include "sadr/ssa/morris_walls.hpp"

#include <string>

#include "sadr/common/periodic.hpp"
#include "sadr/common/status.hpp"
#include "sadr/common/wall_surface.hpp"

namespace sadr::ssa {

std::vector<std::int32_t> assign_morris_walls(const Model& model, const DiffusionGraph& g) {
  const std::size_t n = g.size();
  std::vector<std::int32_t> surface(n, -1);
  for (std::size_t k = model.morris_walls.size(); k-- > 0;) {  // earlier ones overwrite later
    for (const std::uint32_t v : model.morris_walls[k].voxels) {
      if (v >= n) {
        throw InvalidArgument("morris_walls[" + std::to_string(k) + "].voxels contains " +
                                  std::to_string(v) + " (allowed: 0.." + std::to_string(n - 1) +
                                  ")",
                              {{"field", "morris_walls.voxels"}, {"value", std::to_string(v)}});
      }
      if (g.is_wall[v]) surface[v] = static_cast<std::int32_t>(k);
    }
  }
  const auto offset = model.morris_walls.size();
  const WallTangents& t = model.morris_tangents;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const std::uint32_t v = t.particles[k];
    if (v >= n) {
      throw InvalidArgument("morris_tangents[" + std::to_string(k) + "].particle = " +
                                std::to_string(v) + " (allowed: 0.." + std::to_string(n - 1) + ")",
                            {{"field", "morris_tangents.particles"}, {"value", std::to_string(v)}});
    }
    if (g.is_wall[v]) surface[v] = static_cast<std::int32_t>(offset + k);
  }
  return surface;
}

void apply_morris_walls(DiffusionGraph& g, const Model& model, const ParticleState& particles,
                        const std::vector<std::int32_t>& surface) {
  const double h = model.smoothing_length;
  const double* x = particles.positions.data();
  const auto n_surfaces = static_cast<std::int32_t>(model.morris_walls.size());
  const Box& box = model.box;
  auto beta = [&](std::uint32_t fluid, std::uint32_t wall) {
    const std::int32_t w = surface[wall];
    if (w >= n_surfaces) {  // the wall voxel's own tangent plane, from the minimum image
      const auto k = static_cast<std::size_t>(w - n_surfaces);
      double r[3] = {0, 0, 0};
      for (int a = 0; a < box.dimension; ++a) {
        const auto ua = static_cast<std::size_t>(a);
        r[ua] = x[3 * std::size_t{fluid} + ua] - x[3 * std::size_t{wall} + ua];
        if (box.periodic[ua]) r[ua] = minimum_image(r[ua], box.length(a));
      }
      const WallTangents& t = model.morris_tangents;
      return morris_beta(t.depths[k], t.signed_distance(k, r), h);
    }
    const WallSurface& s = model.morris_walls[static_cast<std::size_t>(w)].surface;
    return morris_beta(s.depth(x + 3 * std::size_t{wall}),
                       s.signed_distance(x + 3 * std::size_t{fluid}), h);
  };
  const std::size_t n = g.size();
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t b = g.row_start[i], split = g.split[i], e = g.row_start[i + 1];
    bool touched = false;
    if (g.is_wall[i]) {
      if (surface[i] < 0) continue;
      for (std::uint32_t k = b; k < split; ++k) {  // non-wall targets
        g.edges[k].weight *= beta(g.edges[k].target, i);
        touched = true;
      }
    } else {
      for (std::uint32_t k = split; k < e; ++k) {  // wall targets
        const std::uint32_t j = g.edges[k].target;
        if (surface[j] < 0) continue;
        g.edges[k].weight *= beta(i, j);
        touched = true;
      }
    }
    if (!touched) continue;
    double nowall = 0, wall = 0;
    for (std::uint32_t k = b; k < split; ++k) nowall += g.edges[k].weight;
    for (std::uint32_t k = split; k < e; ++k) wall += g.edges[k].weight;
    g.sum_nowall[i] = nowall;
    g.sum_all[i] = nowall + wall;
  }
}

}  // namespace sadr::ssa
