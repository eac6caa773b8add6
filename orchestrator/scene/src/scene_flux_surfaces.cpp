// SPDX-License-Identifier: MIT
// Scene section "boundary_fluxes", `surface: <body>` (docs/scene-format.md "Surfaces"): the
// first fluid layer next to a fluid or solid body of the geometry section and the shares of its
// area; with `group`, only the part of a mesh body's surface that one physical group of its file
// covers; with `region`, only the part whose first-layer particles lie in that region.
#include <algorithm>
#include <cmath>
#include <string>

#include "sadr/common/status.hpp"
#include "sadr/orchestrator/boundary_share.hpp"
#include "scene_geometry_parts.hpp"

namespace sadr::orchestrator::detail {

namespace {

/// One physical group of a mesh body's surface (boundary_fluxes `group`).
struct SurfaceGroup {
  std::vector<std::uint8_t> part;  ///< per particle: 1 when its nearest surface element is one
                                   ///< of the group's
  std::optional<double> area;      ///< the group's exact area, placed as the body is
  bool inside_box = true;          ///< the group's bounds lie inside the box
};

/// Names of a mesh file's groups of dimension `dim`, sorted.
std::vector<std::string> groups_of(const g::MeshFile& mf, int dim) {
  std::vector<std::string> out;
  for (const auto& [name, gd] : mf.group_dimensions) {
    if (gd == dim) out.push_back(name);
  }
  return out;
}

/// The fluid particles next to `body` whose nearest surface element is one of `group`'s: those
/// no farther from the group (placed as the body) than from the body's whole surface, to 1e-6
/// spacings (a particle as near to two groups, at a corner, belongs to both). Null, with an error
/// said at `gf`, when the body is not a mesh or the file has no such group of dimension d - 1.
std::optional<SurfaceGroup> read_group(SceneContext& ctx, const Field& gf, const GeometryBody& body,
                                       const std::string& group) {
  YamlReader& r = ctx.reader;
  const auto it = ctx.mesh_bodies.find(body.name);
  if (it == ctx.mesh_bodies.end()) {
    r.error(gf, "'group' names a physical group of a mesh file, and the shape of '" + body.name +
                    "' is not a mesh (nor a mesh moved by translate, rotate or scale); allowed: "
                    "'group' on a body of shape type 'mesh', or no 'group' (the whole surface)");
    return std::nullopt;
  }
  const MeshBody& mb = *it->second;
  const g::MeshFile& mf = *mb.file;
  const int d = ctx.scene.box.dimension;
  const std::vector<std::string> surfaces = groups_of(mf, d - 1);
  const std::vector<std::string_view> allowed(surfaces.begin(), surfaces.end());
  const std::string kind =
      d == 3 ? "a surface (dimension 2: triangles)" : "a curve (dimension 1: line segments)";
  const auto dim = mf.group_dimensions.find(group);
  if (dim == mf.group_dimensions.end() || !mf.surfaces.count(group)) {
    std::string msg = "no physical group named '" + group + "' in " + mb.path;
    if (dim != mf.group_dimensions.end()) {
      msg = "physical group '" + group + "' of " + mb.path + " has dimension " +
            std::to_string(dim->second) + "; a part of the surface of a " + std::to_string(d) +
            "D body is " + kind;
    } else if (auto near = nearest_name(group, allowed)) {
      msg += "; did you mean '" + *near + "'?";
    }
    msg += surfaces.empty()
               ? " (the file has no physical group of dimension " + std::to_string(d - 1) + ")"
               : " (allowed: the groups of dimension " + std::to_string(d - 1) + ": " +
                     join_names(allowed) + ")";
    r.error(gf, msg);
    return std::nullopt;
  }
  g::ShapePtr part;
  try {
    part = g::make_mesh_shape(mf.surfaces.at(group));
  } catch (const std::exception& e) {
    r.error(gf, e.what());
    return std::nullopt;
  }
  if (mb.place) part = mb.place(part);
  const GeometryReport& geo = *ctx.scene.geometry;
  const ParticleState& p = ctx.scene.particles;
  SurfaceGroup out;
  out.area = part->exact_area();
  const g::Aabb pb = part->bounds();
  for (int a = 0; a < d; ++a) {
    const auto ua = static_cast<std::size_t>(a);
    out.inside_box =
        out.inside_box && pb.lo[a] > ctx.scene.box.lo[ua] && pb.hi[a] < ctx.scene.box.hi[ua];
  }
  out.part.assign(p.size(), 0);
  const double tol = 1e-6 * geo.spacing;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kind(i) != ParticleKind::kFluid || geo.surface_id[i] != body.surface_id) continue;
    const g::Vec3 x{p.positions[3 * i], p.positions[3 * i + 1], p.positions[3 * i + 2]};
    const double to_part = std::abs(part->signed_distance(x));
    const double to_body = std::abs(mb.shape->signed_distance(x));
    out.part[i] = to_part <= to_body + tol ? 1 : 0;
  }
  return out;
}

}  // namespace

bool read_surface_share(SceneContext& ctx, const Field& f, const Field& root,
                        const std::string& name, Reaction& rx) {
  YamlReader& r = ctx.reader;
  const Field sf = YamlReader::child(f, "surface");
  const Field gf = YamlReader::child(f, "group");
  const Field rf = YamlReader::child(f, "region");
  if (!YamlReader::present(YamlReader::child(root, "geometry"))) {
    r.error(sf,
            "'surface' names a fluid or solid body of the 'geometry' section, and the scene "
            "has none; allowed: 'face' (a box face)");
    return false;
  }
  const auto group = YamlReader::present(gf) ? r.string(f, "group", true) : std::nullopt;
  if (YamlReader::present(gf) && !group) return false;
  if (!ctx.geometry_ok || !ctx.particles_ok || !ctx.scene.geometry) return false;
  const GeometryReport& geo = *ctx.scene.geometry;
  const GeometryBody* body = nullptr;
  std::vector<std::string> own;
  for (const auto& b : geo.bodies) {
    if (b.name == name) body = &b;
    if (b.role != "region") own.push_back(b.name);
  }
  const std::vector<std::string_view> allowed(own.begin(), own.end());
  if (!body) {
    std::string msg = "unknown surface '" + name + "'";
    if (auto near = nearest_name(name, allowed)) msg += "; did you mean '" + *near + "'?";
    r.error(sf, msg + " (allowed: the fluid and solid bodies of 'geometry': " +
                    join_names(allowed) + ")");
    return false;
  }
  if (body->role == "region") {
    r.error(sf, "'" + name +
                    "' is a region body, which has no surface (no walls); allowed: a "
                    "fluid or solid body (" +
                    join_names(allowed) + ")");
    return false;
  }
  const Region* region = nullptr;
  if (auto rn = r.string(f, "region", false)) {
    region = lookup_region(ctx, rf, *rn);
    if (!region) return false;
  } else if (YamlReader::present(rf)) {
    return false;
  }
  // The shape's own area when it gives one and nothing of it is cut off by the box.
  std::optional<double> area;
  if (body->exact_area && body->inside_box) area = body->exact_area;
  std::vector<std::uint8_t> part;
  std::string what = "'" + name + "'";
  std::string why = body->exact_area ? "cut by the box" : "not known in closed form";
  if (group) {
    auto sg = read_group(ctx, gf, *body, *group);
    if (!sg) return false;
    part = std::move(sg->part);
    area = sg->inside_box ? sg->area : std::nullopt;
    what = "group '" + *group + "' of '" + name + "'";
    why = sg->inside_box ? "not known in closed form (a non-uniform scale)" : "cut by the box";
  }
  const Field at = group ? gf : sf;
  try {
    BoundaryShare s = surface_share(ctx.scene.particles, geo.surface_id, geo.surface_distance,
                                    body->surface_id, geo.spacing, area, part);
    if (area && !(s.layer_area > 0.5 * *area && s.layer_area < 2.0 * *area)) {
      r.warning(at, "the first fluid layer next to " + what + " covers about " +
                        format_number(s.layer_area) + " of its area " + format_number(*area) +
                        " (part of the surface lies inside another solid or outside the fluid "
                        "body?); the flux uses the layer's estimate " +
                        format_number(s.layer_area));
      s = surface_share(ctx.scene.particles, geo.surface_id, geo.surface_distance, body->surface_id,
                        geo.spacing, std::nullopt, part);
    }
    if (!area) {
      r.warning(at, "the area of " + what + " is " + why +
                        ": the flux uses its first fluid layer's estimate " +
                        format_number(s.layer_area) +
                        ", accurate to about a spacing over the surface's radius of curvature; "
                        "for an exact area use a primitive or a mesh wholly inside the box");
    }
    if (region) {  // the part of the layer in the region, with the shares it had
      BoundaryShare kept;
      for (std::size_t k = 0; k < s.particles.size(); ++k) {
        const auto& in = region->particles;
        if (!std::binary_search(in.begin(), in.end(), s.particles[k])) continue;
        kept.particles.push_back(s.particles[k]);
        kept.areas.push_back(s.areas[k]);
        kept.area += s.areas[k];
      }
      if (kept.particles.empty()) {
        r.error(rf, "boundary flux '" + rx.name +
                        "': no particle of the first fluid layer next "
                        "to " +
                        what + " lies in region '" + region->name +
                        "'; allowed: a region that holds part of that layer");
        return false;
      }
      s = std::move(kept);
    }
    rx.boundary_particles = std::move(s.particles);
    rx.boundary_areas = std::move(s.areas);
  } catch (const InvalidArgument& e) {
    r.error(at, "boundary flux '" + rx.name + "' on " + (group ? what : "surface " + what) + ": " +
                    e.what());
    return false;
  }
  return true;
}

}  // namespace sadr::orchestrator::detail
