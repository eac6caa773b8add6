// SPDX-License-Identifier: MIT
// `surface: <body>` and `group: <name>` (docs/scene-format.md "Surfaces"): the body of the
// geometry section a key names, and the particles next to (fluid) or behind (walls) the part of
// a mesh body's surface that one physical group of its file covers. Shared by boundary_fluxes
// (scene_flux_surfaces.cpp: the fluid layer next to it) and species boundaries
// (scene_chemistry.cpp: the walls behind it).
#include <cmath>
#include <string>

#include "scene_geometry_parts.hpp"

namespace sadr::orchestrator::detail {

namespace {

/// Names of a mesh file's groups of dimension `dim`, sorted.
std::vector<std::string> groups_of(const g::MeshFile& mf, int dim) {
  std::vector<std::string> out;
  for (const auto& [name, gd] : mf.group_dimensions) {
    if (gd == dim) out.push_back(name);
  }
  return out;
}

}  // namespace

const GeometryBody* surface_body(SceneContext& ctx, const Field& sf, const std::string& name) {
  YamlReader& r = ctx.reader;
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
    return nullptr;
  }
  if (body->role == "region") {
    r.error(sf, "'" + name +
                    "' is a region body, which has no surface (no walls); allowed: a "
                    "fluid or solid body (" +
                    join_names(allowed) + ")");
    return nullptr;
  }
  return body;
}

std::optional<SurfaceGroup> read_surface_group(SceneContext& ctx, const Field& gf,
                                               const GeometryBody& body, const std::string& group,
                                               ParticleKind kind) {
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
  const std::string dims =
      d == 3 ? "a surface (dimension 2: triangles)" : "a curve (dimension 1: line segments)";
  const auto dim = mf.group_dimensions.find(group);
  if (dim == mf.group_dimensions.end() || !mf.surfaces.count(group)) {
    std::string msg = "no physical group named '" + group + "' in " + mb.path;
    if (dim != mf.group_dimensions.end()) {
      msg = "physical group '" + group + "' of " + mb.path + " has dimension " +
            std::to_string(dim->second) + "; a part of the surface of a " + std::to_string(d) +
            "D body is " + dims;
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
    if (p.kind(i) != kind || geo.surface_id[i] != body.surface_id) continue;
    const g::Vec3 x{p.positions[3 * i], p.positions[3 * i + 1], p.positions[3 * i + 2]};
    const double to_part = std::abs(part->signed_distance(x));
    const double to_body = std::abs(mb.shape->signed_distance(x));
    out.part[i] = to_part <= to_body + tol ? 1 : 0;
  }
  return out;
}

std::optional<std::vector<std::uint32_t>> surface_walls(SceneContext& ctx, const Field& f,
                                                        const Field& root) {
  YamlReader& r = ctx.reader;
  const Field sf = YamlReader::child(f, "surface");
  const Field gf = YamlReader::child(f, "group");
  if (!YamlReader::present(YamlReader::child(root, "geometry"))) {
    r.error(sf,
            "'surface' names a fluid or solid body of the 'geometry' section, and the scene "
            "has none; allowed: 'region'");
    return std::nullopt;
  }
  const auto name = r.string(f, "surface", true);
  const auto group = YamlReader::present(gf) ? r.string(f, "group", true) : std::nullopt;
  if (!name || (YamlReader::present(gf) && !group)) return std::nullopt;
  if (!ctx.geometry_ok || !ctx.particles_ok || !ctx.scene.geometry) return std::nullopt;
  const GeometryBody* body = surface_body(ctx, sf, *name);
  if (!body) return std::nullopt;
  const GeometryReport& geo = *ctx.scene.geometry;
  const ParticleState& p = ctx.scene.particles;
  std::vector<std::uint8_t> part;
  if (group) {
    auto sg = read_surface_group(ctx, gf, *body, *group, ParticleKind::kWall);
    if (!sg) return std::nullopt;
    part = std::move(sg->part);
  }
  std::vector<std::uint32_t> walls;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kind(i) != ParticleKind::kWall || geo.surface_id[i] != body->surface_id) continue;
    if (group && !part[i]) continue;
    walls.push_back(static_cast<std::uint32_t>(i));
  }
  if (walls.empty()) {
    r.error(group ? gf : sf, "no wall particle lies behind " +
                                 (group ? "group '" + *group + "' of '" + *name + "'"
                                        : "the surface of '" + *name + "'") +
                                 " (every wall particle of '" + *name +
                                 "' is nearer another part of its surface, or the surface has "
                                 "no walls); allowed: a part of the surface with walls behind it");
    return std::nullopt;
  }
  return walls;
}

}  // namespace sadr::orchestrator::detail
