// SPDX-License-Identifier: MIT
// Scene section "geometry": what is measured of the particles made from the bodies: the exact
// fluid volume where the shapes give it, and the thickness of solids and fluid gaps.
#include <algorithm>
#include <cmath>
#include <functional>

#include "scene_geometry_parts.hpp"

namespace sadr::orchestrator::detail {

namespace {

/// Volume (area in 2D) of the part of an axis-aligned box inside the scene box.
double clipped_box_volume(const g::Aabb& a, const Box& b) {
  double v = 1.0;
  for (int k = 0; k < b.dimension; ++k) {
    const auto uk = static_cast<std::size_t>(k);
    v *= std::max(0.0, std::min(a.hi[k], b.hi[uk]) - std::max(a.lo[k], b.lo[uk]));
  }
  return v;
}

/// Distance along `dir` from x, inside `sd` (< 0), to where sd turns positive; nullopt beyond
/// `limit` or outside the box.
std::optional<double> exit_distance(const std::function<double(g::Vec3)>& sd, g::Vec3 x,
                                    g::Vec3 dir, double limit, double step_min, const g::Aabb& box,
                                    int d) {
  double t = 0.0;
  for (int it = 0; it < 400 && t <= limit; ++it) {
    const g::Vec3 p = x + t * dir;
    for (int k = 0; k < d; ++k) {
      if (p[k] < box.lo[k] || p[k] > box.hi[k]) return std::nullopt;
    }
    const double v = sd(p);
    if (v >= 0) return t;
    t += std::max(-v, step_min);
  }
  return std::nullopt;
}

g::Vec3 gradient(const std::function<double(g::Vec3)>& sd, g::Vec3 x, double eps, int d) {
  g::Vec3 n;
  for (int k = 0; k < d; ++k) {
    g::Vec3 a = x, b = x;
    a[k] += eps;
    b[k] -= eps;
    n[k] = (sd(a) - sd(b)) / (2 * eps);
  }
  return g::normalized(n);
}
}  // namespace

/// The fluid volume, where the shapes give it: the body's exact volume (or its clipped box, or
/// the box) minus solids whose bounding boxes lie inside the body and apart from each other.
std::optional<double> exact_fluid_volume(const g::FluidDomain& dom, const ShapeRead* body,
                                         const Box& box) {
  const int d = box.dimension;
  const g::Aabb bx = box_aabb(box);
  double v = 0.0;
  if (!body) {
    v = clipped_box_volume(bx, box);
  } else if (body->plain_box) {
    v = clipped_box_volume(body->shape->bounds(), box);
  } else {
    const auto e = body->shape->exact_volume();
    const g::Aabb bb = body->shape->bounds();
    const double btol = 1e-9 * g::norm(bx.extent());
    bool inside = e.has_value();
    for (int k = 0; k < d && inside; ++k) {
      inside = bb.lo[k] >= bx.lo[k] - btol && bb.hi[k] <= bx.hi[k] + btol;
    }
    if (!inside) return std::nullopt;
    v = *e;
  }
  const double tol = 1e-9 * g::norm(bx.extent());
  std::vector<g::Aabb> seen;
  for (const auto& s : dom.solids) {
    const auto e = s.shape->exact_volume();
    if (!e) return std::nullopt;
    const g::Aabb sb = s.shape->bounds();
    for (const auto& o : seen) {
      if (!g::intersect(o, sb).empty()) return std::nullopt;
    }
    seen.push_back(sb);
    // Every corner of the solid's bounds in the fluid body (or the box).
    for (int c = 0; c < (d == 3 ? 8 : 4); ++c) {
      const g::Vec3 p{(c & 1) ? sb.hi.x : sb.lo.x, (c & 2) ? sb.hi.y : sb.lo.y,
                      d == 3 ? ((c & 4) ? sb.hi.z : sb.lo.z) : 0.0};
      if (!bx.inflated(tol).contains(p)) return std::nullopt;  // cut by the box
      if (dom.body && !(dom.body->signed_distance(p) < 0)) return std::nullopt;
    }
    v -= *e;
  }
  return v;
}

/// Thickness of solids (walls behind a solid's surface, marched into the solid) and of fluid
/// gaps (fluid next to a surface, marched away from it), along the surface normal, from every
/// particle within one spacing of a surface; per surface id.
std::map<int, std::pair<Thin, Thin>> measure_features(const g::ParticleSet& p,
                                                      const g::FluidDomain& dom,
                                                      const std::map<int, g::ShapePtr>& solids,
                                                      double h, double limit) {
  std::map<int, std::pair<Thin, Thin>> out;  // id -> (solid, fluid gap)
  const double dx = p.spacing;
  const int d = p.dimension;
  const g::Aabb box = dom.box;
  const std::function<double(g::Vec3)> fluid_sd = [&](g::Vec3 q) {
    return g::fluid_signed_distance(dom, q);
  };
  for (std::size_t i = 0; i < p.size(); ++i) {
    const int id = p.surface_id[i];
    if (id < 0 || !(p.distance[i] < dx)) continue;
    if (p.kind[i] == g::Kind::kWall) {
      const auto it = solids.find(id);
      if (it == solids.end()) continue;  // the fluid body's outside is not a feature
      const g::ShapePtr shape = it->second;
      const std::function<double(g::Vec3)> sd = [&](g::Vec3 q) {
        return shape->signed_distance(q);
      };
      const g::Vec3 dir = -1.0 * p.normal[i];
      const auto t = exit_distance(sd, p.position[i], dir, limit, 0.02 * dx, box, d);
      if (!t) continue;
      Thin& th = out[id].first;
      const double w = *t + p.distance[i];
      if (w < h) ++th.count;
      if (w < th.thickness) th.thickness = w, th.where = p.position[i];
    } else {
      const g::Vec3 dir = -1.0 * gradient(fluid_sd, p.position[i], 1e-3 * dx, d);
      if (!(g::norm(dir) > 0)) continue;
      const auto t = exit_distance(fluid_sd, p.position[i], dir, limit, 0.02 * dx, box, d);
      if (!t) continue;
      Thin& th = out[id].second;
      const double w = *t + p.distance[i];
      if (w < h) ++th.count;
      if (w < th.thickness) th.thickness = w, th.where = p.position[i];
    }
  }
  return out;
}
}  // namespace sadr::orchestrator::detail
