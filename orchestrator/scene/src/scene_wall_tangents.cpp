// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/scene_wall_tangents.hpp"

#include <algorithm>
#include <cmath>

namespace sadr::orchestrator {

WallTangents scene_wall_tangents(const Scene& scene) {
  WallTangents t;
  const GeometryReport* g = scene.geometry.get();
  if ((scene.fluid.wall_model != "morris" && scene.fluid.wall_model != "adami") ||
      !scene.fluid.wall_planes.empty() || !g) {
    return t;
  }
  const ParticleState& p = scene.particles;
  const std::size_t n = p.size();
  if (g->surface_distance.size() != n || g->surface_normal.size() != n) return t;
  for (std::size_t i = 0; i < n; ++i) {
    if (p.kind(i) != ParticleKind::kWall) continue;
    const auto& v = g->surface_normal[i];
    const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    const double depth = g->surface_distance[i];
    if (!(len > 0) || !std::isfinite(depth)) continue;  // no surface: a plain wall particle
    t.particles.push_back(static_cast<std::uint32_t>(i));
    t.depths.push_back(std::max(depth, 0.0));
    for (const double c : v) t.normals.push_back(c / len);
  }
  return t;
}

}  // namespace sadr::orchestrator
