// SPDX-License-Identifier: MIT
// Scene section "geometry": particles from bodies (shapes, CSG, meshes) through the geometry
// library (docs/geometry.md): a fluid domain, solid bodies with wall layers, named regions and
// surface layers; instead of the section "particles".
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <set>

#include "sadr/common/status.hpp"
#include "sadr/geometry/mesh.hpp"
#include "sadr/geometry/mesh_io.hpp"
#include "sadr/geometry/particles.hpp"
#include "sadr/geometry/shape.hpp"
#include "sadr/orchestrator/hash.hpp"
#include "sadr/orchestrator/scene_geometry.hpp"
#include "scene_parts.hpp"

namespace sadr::orchestrator {
namespace detail {

namespace {

namespace g = sadr::geometry;

constexpr std::array<std::string_view, 7> kGeometryKeys{
    "spacing", "lattice", "density", "wall_depth", "offset", "relax", "bodies"};
constexpr std::array<std::string_view, 7> kBodyKeys{
    "name", "role", "shape", "wall_layer", "fluid_layer", "layer_thickness", "kinds"};
constexpr std::array<std::string_view, 18> kShapeKeys{
    "type",   "lower", "upper",        "center",       "radius",   "radii",
    "start",  "end",   "major_radius", "minor_radius", "vertices", "z",
    "shapes", "file",  "group",        "translate",    "rotate",   "scale"};
constexpr std::array<std::string_view, 2> kRelaxKeys{"tolerance", "max_iterations"};
constexpr std::array<std::string_view, 2> kRotateKeys{"axis", "angle"};
constexpr std::array<std::string_view, 14> kShapeTypes{
    "box",   "sphere",  "disk",      "ellipsoid", "ellipse",      "cylinder",   "capsule",
    "torus", "polygon", "extrusion", "union",     "intersection", "difference", "mesh"};
constexpr std::array<std::string_view, 3> kRoles{"fluid", "solid", "region"};
constexpr std::array<std::string_view, 2> kLattices{"cubic", "hexagonal"};
constexpr std::array<std::string_view, 4> kKindNames{"fluid", "wall", "inlet", "outlet"};
constexpr double kMaxSites = 5e7;
constexpr int kMaxDepth = 32;
constexpr double kInf = std::numeric_limits<double>::infinity();

/// The keys each shape type takes besides type, translate, rotate and scale.
std::vector<std::string_view> type_keys(std::string_view type) {
  if (type == "box") return {"lower", "upper"};
  if (type == "sphere" || type == "disk") return {"center", "radius"};
  if (type == "ellipsoid" || type == "ellipse") return {"center", "radii"};
  if (type == "cylinder" || type == "capsule") return {"start", "end", "radius"};
  if (type == "torus") return {"center", "major_radius", "minor_radius"};
  if (type == "polygon") return {"vertices"};
  if (type == "extrusion") return {"vertices", "z"};
  if (type == "mesh") return {"file", "group"};
  return {"shapes"};  // union, intersection, difference
}

/// The dimension a type needs (0: both).
int type_dimension(std::string_view type) {
  if (type == "disk" || type == "ellipse" || type == "polygon") return 2;
  if (type == "sphere" || type == "ellipsoid" || type == "cylinder" || type == "torus" ||
      type == "extrusion") {
    return 3;
  }
  return 0;
}

std::string_view other_name(std::string_view type) {
  if (type == "disk") return "sphere";
  if (type == "sphere") return "disk";
  if (type == "ellipse") return "ellipsoid";
  if (type == "ellipsoid") return "ellipse";
  if (type == "polygon") return "extrusion";
  if (type == "extrusion") return "polygon";
  if (type == "cylinder") return "box, disk or capsule";
  return "another shape";
}

g::Vec3 to_vec(const std::array<double, 3>& a) {
  return {a[0], a[1], a[2]};
}

std::string point_text(g::Vec3 p, int d) {
  char buf[96];
  if (d == 3) {
    std::snprintf(buf, sizeof buf, "(%.4g, %.4g, %.4g)", p.x, p.y, p.z);
  } else {
    std::snprintf(buf, sizeof buf, "(%.4g, %.4g)", p.x, p.y);
  }
  return buf;
}

/// One shape read from the scene, and what is known of it.
struct ShapeRead {
  g::ShapePtr shape;
  bool plain_box = false;  ///< an axis-aligned box, translated at most (bounds exact)
};

struct BodyRead {
  std::string name;
  std::string role;
  Field field;
  Field shape_field;
  ShapeRead shape;
  std::string wall_layer, fluid_layer;
  double layer_thickness = 0.0;
  std::vector<ParticleKind> kinds;
  int surface_id = -1;
};

class GeometryReader {
 public:
  GeometryReader(SceneContext& ctx, int d) : ctx_(ctx), r_(ctx.reader), d_(d) {}

  ShapeRead read_shape(const Field& f, int depth);
  std::vector<std::string>& notes() { return notes_; }

 private:
  ShapeRead primitive(const Field& f, std::string_view type);
  ShapeRead mesh(const Field& f);
  ShapeRead transform(const Field& f, ShapeRead s);
  std::optional<std::vector<g::Vec3>> vertices(const Field& f);

  SceneContext& ctx_;
  YamlReader& r_;
  int d_;
  std::map<std::string, g::MeshFile> meshes_;
  std::vector<std::string> notes_;
};

std::optional<std::vector<g::Vec3>> GeometryReader::vertices(const Field& f) {
  const Field list = YamlReader::child(f, "vertices");
  if (!YamlReader::present(list)) {
    r_.error(list,
             "missing; required: a list of at least 3 points [x, y], e.g. [[0, 0], [1, 0], "
             "[0, 1]]");
    return std::nullopt;
  }
  if (!list.node.IsSequence() || list.node.size() < 3) {
    r_.error(list, "expected a list of at least 3 points [x, y]");
    return std::nullopt;
  }
  std::vector<g::Vec3> out;
  bool ok = true;
  for (std::size_t i = 0; i < list.node.size(); ++i) {
    const Field e = YamlReader::element(list, i);
    if (!e.node.IsSequence() || e.node.size() != 2) {
      r_.error(e, "expected a point [x, y] (2 numbers)");
      ok = false;
      continue;
    }
    const auto x = r_.number_at(YamlReader::element(e, 0), Bound::kAny, "length");
    const auto y = r_.number_at(YamlReader::element(e, 1), Bound::kAny, "length");
    if (!x || !y) {
      ok = false;
      continue;
    }
    out.push_back({*x, *y, 0.0});
  }
  if (!ok) return std::nullopt;
  return out;
}

ShapeRead GeometryReader::primitive(const Field& f, std::string_view type) {
  ShapeRead out;
  const int d = d_;
  if (type == "box") {
    const auto lo = r_.vector(f, "lower", d, "length", true);
    const auto hi = r_.vector(f, "upper", d, "length", true);
    if (!lo || !hi) return out;
    for (int a = 0; a < d; ++a) {
      const auto ua = static_cast<std::size_t>(a);
      if (!((*hi)[ua] > (*lo)[ua])) {
        r_.error(YamlReader::child(f, "upper"),
                 std::string("axis ") + "xyz"[a] + ": upper " + format_number((*hi)[ua]) +
                     " must be greater than lower " + format_number((*lo)[ua]));
        return out;
      }
    }
    out.shape = g::make_box(to_vec(*lo), to_vec(*hi), d);
    out.plain_box = true;
  } else if (type == "sphere" || type == "disk") {
    const auto c = r_.vector(f, "center", d, "length", true);
    const auto rad = r_.number(f, "radius", Bound::kPositive, "length", true);
    if (c && rad) out.shape = g::make_sphere(to_vec(*c), *rad, d);
  } else if (type == "ellipsoid" || type == "ellipse") {
    const auto c = r_.vector(f, "center", d, "length", true);
    const auto radii = r_.vector(f, "radii", d, "length", true);
    if (!c || !radii) return out;
    for (int a = 0; a < d; ++a) {
      if (!((*radii)[static_cast<std::size_t>(a)] > 0)) {
        r_.error(YamlReader::child(f, "radii"),
                 format_number((*radii)[static_cast<std::size_t>(a)]) +
                     " is out of range; allowed: every semi-axis > 0 [length]");
        return out;
      }
    }
    out.shape = g::make_ellipsoid(to_vec(*c), to_vec(*radii), d);
  } else if (type == "cylinder" || type == "capsule") {
    const auto a = r_.vector(f, "start", d, "length", true);
    const auto b = r_.vector(f, "end", d, "length", true);
    const auto rad = r_.number(f, "radius", Bound::kPositive, "length", true);
    if (!a || !b || !rad) return out;
    if (*a == *b && type == "cylinder") {
      r_.error(YamlReader::child(f, "end"), "equals start; allowed: an axis of length > 0");
      return out;
    }
    out.shape = type == "cylinder" ? g::make_cylinder(to_vec(*a), to_vec(*b), *rad)
                                   : g::make_capsule(to_vec(*a), to_vec(*b), *rad, d);
  } else if (type == "torus") {
    const auto c = r_.vector(f, "center", d, "length", true);
    const auto big = r_.number(f, "major_radius", Bound::kPositive, "length", true);
    const auto small = r_.number(f, "minor_radius", Bound::kPositive, "length", true);
    if (!c || !big || !small) return out;
    if (!(*small < *big)) {
      r_.error(YamlReader::child(f, "minor_radius"),
               format_number(*small) + " is out of range; allowed: minor_radius < major_radius (" +
                   format_number(*big) + ")");
      return out;
    }
    out.shape = g::make_torus(to_vec(*c), *big, *small);
  } else if (type == "polygon" || type == "extrusion") {
    auto v = vertices(f);
    if (type == "polygon") {
      if (v) out.shape = g::make_polygon(std::move(*v));
    } else {
      const auto z = r_.vector(f, "z", 2, "length", true);
      if (z && !((*z)[1] > (*z)[0])) {
        r_.error(YamlReader::child(f, "z"), "expected [z0, z1] with z1 > z0");
        return out;
      }
      if (v && z) out.shape = g::make_extrusion(std::move(*v), (*z)[0], (*z)[1]);
    }
  }
  return out;
}

ShapeRead GeometryReader::mesh(const Field& f) {
  ShapeRead out;
  const auto name = r_.string(f, "file", true);
  if (!name) return out;
  const Field file = YamlReader::child(f, "file");
  const std::filesystem::path path = std::filesystem::path(*name).is_absolute()
                                         ? std::filesystem::path(*name)
                                         : ctx_.base_dir / *name;
  const std::string key = path.lexically_normal().string();
  auto it = meshes_.find(key);
  if (it == meshes_.end()) {
    try {
      it = meshes_.emplace(key, g::read_mesh(key, d_)).first;
      // A changed mesh is a changed scene (checkpoints refuse it): its hash joins the scene's.
      ctx_.particle_file_bytes += "\nmesh " + file_hash(key);
    } catch (const std::exception& e) {
      r_.error(file, std::string(e.what()) +
                         " (mesh files: .stl or .msh, paths relative to the scene file's "
                         "directory)");
      return out;
    }
  }
  const g::MeshFile& mf = it->second;
  const g::SurfaceMesh* surface = &mf.boundary;
  const Field group = YamlReader::child(f, "group");
  if (YamlReader::present(group)) {
    const auto gname = r_.string(f, "group", false);
    if (!gname) return out;
    if (mf.regions.count(*gname)) {
      surface = &mf.regions.at(*gname);
    } else if (mf.surfaces.count(*gname)) {
      surface = &mf.surfaces.at(*gname);
    } else {
      std::vector<std::string> names = mf.region_names();
      for (const auto& s : mf.surface_names()) names.push_back(s);
      std::vector<std::string_view> views(names.begin(), names.end());
      std::string msg = "no physical group named '" + *gname + "' in " + key;
      if (auto near = nearest_name(*gname, views)) msg += "; did you mean '" + *near + "'?";
      msg += names.empty() ? " (the file has no named physical groups; remove 'group' to use "
                             "the whole mesh)"
                           : " (allowed: " + join_names(views) + ")";
      r_.error(group, msg);
      return out;
    }
  }
  try {
    auto m = g::make_mesh_shape(*surface);
    if (m->was_inverted()) {
      const std::string note = "the mesh " + key +
                               " has inward normals (negative enclosed volume); read with them "
                               "flipped";
      notes_.push_back(note);
      r_.warning(file, note + " (nothing to do unless the inside was meant to be the outside)");
    }
    out.shape = m;
  } catch (const std::exception& e) {
    r_.error(file, std::string(e.what()) + " (expected a closed surface mesh)");
  }
  return out;
}

ShapeRead GeometryReader::transform(const Field& f, ShapeRead s) {
  if (!s.shape) return s;
  const Field sc = YamlReader::child(f, "scale");
  if (YamlReader::present(sc)) {
    g::Vec3 factors{1, 1, 1};
    bool ok = true;
    if (sc.node.IsScalar()) {
      const auto v = r_.number_at(sc, Bound::kPositive, "dimensionless");
      ok = v.has_value();
      if (v) factors = {*v, *v, d_ == 3 ? *v : 1.0};
    } else if (auto v = r_.vector(f, "scale", d_, "dimensionless", true)) {
      for (int a = 0; a < d_; ++a) {
        if (!((*v)[static_cast<std::size_t>(a)] > 0)) {
          r_.error(sc, "every factor must be > 0; allowed: a number > 0 or " + std::to_string(d_) +
                           " numbers > 0");
          ok = false;
        }
      }
      if (ok) factors = {(*v)[0], (*v)[1], d_ == 3 ? (*v)[2] : 1.0};
    } else {
      ok = false;
    }
    if (!ok) return {};
    s.shape = g::scale(s.shape, factors);
    s.plain_box = false;
  }
  const Field rot = YamlReader::child(f, "rotate");
  if (YamlReader::present(rot)) {
    g::Vec3 axis{0, 0, 1};
    std::optional<double> angle;
    if (d_ == 2) {
      if (!rot.node.IsScalar()) {
        r_.error(rot, "expected an angle in degrees (counter-clockwise about the origin)");
        return {};
      }
      angle = r_.number_at(rot, Bound::kAny, "degrees");
    } else {
      if (!r_.expect_map(rot, kRotateKeys)) return {};
      const auto ax = r_.vector(rot, "axis", 3, "dimensionless", true);
      angle = r_.number(rot, "angle", Bound::kAny, "degrees", true);
      if (ax) {
        axis = to_vec(*ax);
        if (!(g::norm(axis) > 0)) {
          r_.error(YamlReader::child(rot, "axis"), "is zero; allowed: a non-zero direction");
          return {};
        }
      }
      if (!ax) return {};
    }
    if (!angle) return {};
    s.shape = g::rotate(s.shape, axis, *angle * std::numbers::pi / 180.0);
    s.plain_box = false;
  }
  if (YamlReader::present(YamlReader::child(f, "translate"))) {
    const auto t = r_.vector(f, "translate", d_, "length", true);
    if (!t) return {};
    s.shape = g::translate(s.shape, to_vec(*t));
  }
  return s;
}

ShapeRead GeometryReader::read_shape(const Field& f, int depth) {
  if (!YamlReader::present(f)) {
    r_.error(f, "missing; required: a shape, e.g. {type: disk, center: [0.5, 0.5], radius: 0.1}");
    return {};
  }
  if (depth > kMaxDepth) {
    r_.error(f, "shapes nested deeper than 32 levels; allowed: at most 32");
    return {};
  }
  if (!r_.expect_map(f, kShapeKeys)) return {};
  const auto type = r_.choice(f, "type", kShapeTypes, true, "shape type");
  if (!type) return {};
  const Field tf = YamlReader::child(f, "type");
  const int need = type_dimension(*type);
  if (need != 0 && need != d_) {
    r_.error(tf, "shape type '" + *type + "' is " + std::to_string(need) + "D, the scene " +
                     std::to_string(d_) + "D; use '" + std::string(other_name(*type)) + "'");
    return {};
  }
  const auto keys = type_keys(*type);
  bool ok = true;
  for (const auto& k : kShapeKeys) {
    if (k == "type" || k == "translate" || k == "rotate" || k == "scale") continue;
    const Field c = YamlReader::child(f, k);
    if (YamlReader::present(c) && std::find(keys.begin(), keys.end(), k) == keys.end()) {
      std::vector<std::string_view> all(keys.begin(), keys.end());
      for (const auto t : {"translate", "rotate", "scale"}) all.push_back(t);
      r_.error(c, "key '" + std::string(k) + "' does not apply to shape type '" + *type +
                      "' (its keys: " + join_names(all) + ")");
      ok = false;
    }
  }
  if (!ok) return {};
  ShapeRead out;
  try {
    if (*type == "union" || *type == "intersection" || *type == "difference") {
      const Field list = YamlReader::child(f, "shapes");
      const std::size_t least = *type == "difference" ? 2 : 1;
      if (!YamlReader::present(list) || !list.node.IsSequence() || list.node.size() < least) {
        r_.error(YamlReader::present(list) ? list : f,
                 std::string(YamlReader::present(list) ? "" : "shapes: ") + "'" + *type +
                     "' of nothing; required: 'shapes', a list of at least " +
                     std::to_string(least) + " shapes" +
                     (*type == "difference" ? " (the first minus the others)" : ""));
        return {};
      }
      std::vector<g::ShapePtr> children;
      for (std::size_t i = 0; i < list.node.size(); ++i) {
        ShapeRead c = read_shape(YamlReader::element(list, i), depth + 1);
        if (!c.shape) ok = false;
        children.push_back(c.shape);
      }
      if (!ok) return {};
      if (*type == "union") {
        out.shape = g::csg_union(std::move(children));
      } else if (*type == "intersection") {
        out.shape = g::csg_intersection(std::move(children));
      } else {
        g::ShapePtr first = children.front();
        children.erase(children.begin());
        out.shape = g::csg_difference(std::move(first), std::move(children));
      }
    } else if (*type == "mesh") {
      out = mesh(f);
    } else {
      out = primitive(f, *type);
    }
    return transform(f, out);
  } catch (const std::exception& e) {  // the library's own checks (InvalidArgument)
    r_.error(f, e.what());
    return {};
  }
}

g::Aabb box_aabb(const Box& b) {
  return {{b.lo[0], b.lo[1], b.lo[2]}, {b.hi[0], b.hi[1], b.hi[2]}};
}

/// Volume (area in 2D) of the part of an axis-aligned box inside the scene box.
double clipped_box_volume(const g::Aabb& a, const Box& b) {
  double v = 1.0;
  for (int k = 0; k < b.dimension; ++k) {
    const auto uk = static_cast<std::size_t>(k);
    v *= std::max(0.0, std::min(a.hi[k], b.hi[uk]) - std::max(a.lo[k], b.lo[uk]));
  }
  return v;
}

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

struct Thin {
  double thickness = kInf;
  g::Vec3 where{};
  std::size_t count = 0;  ///< surface particles where the feature is thinner than h
};

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

void add_region(SceneContext& ctx, const std::string& name, std::vector<std::uint32_t> members,
                const std::vector<ParticleKind>& kinds) {
  Region rg;
  rg.name = name;
  rg.shape = RegionShape::kIds;
  rg.ids = std::move(members);
  rg.kinds = kinds;
  resolve_membership(rg, ctx.scene.particles, ctx.tolerance());
  ctx.scene.regions.push_back(std::move(rg));
}

}  // namespace

void read_geometry(SceneContext& ctx, const Field& root) {
  YamlReader& r = ctx.reader;
  Scene& s = ctx.scene;
  const Field geo = YamlReader::child(root, "geometry");
  const Field particles = YamlReader::child(root, "particles");
  if (YamlReader::present(particles)) {
    r.error(particles,
            "'particles' and 'geometry' both make the particles; give one: 'geometry' (bodies: "
            "a fluid domain, solids, regions) or 'particles' (a lattice with fill rules, or a "
            "particle file)");
  }
  if (!r.expect_map(geo, kGeometryKeys)) return;
  const std::size_t errors_before = r.diag().size();
  const int d = s.box.dimension;
  if (ctx.dimension_ok && d == 1) {
    r.error(geo, "needs dimension 2 or 3 (the scene is 1D); use 'particles' in 1D");
    return;
  }
  const auto dx = r.number(geo, "spacing", Bound::kPositive, "length", true);
  if (dx) s.lattice_spacing = *dx;
  if (ctx.h_over_dx) {
    if (dx) s.fluid.smoothing_length = *ctx.h_over_dx * *dx;
  }
  const double h = s.fluid.smoothing_length;
  g::Lattice lattice = g::Lattice::kCubic;
  std::string lattice_name = "cubic";
  if (auto l = r.choice(geo, "lattice", kLattices, false, "lattice")) {
    lattice_name = *l;
    lattice = *l == "hexagonal" ? g::Lattice::kHexagonal : g::Lattice::kCubic;
  }
  const double density =
      r.number_or(geo, "density", s.fluid.reference_density, Bound::kPositive, "mass/length^d");
  const double wall_depth = r.number_or(geo, "wall_depth", h, Bound::kNonNegative, "length");
  g::Vec3 offset{};
  if (ctx.dimension_ok) {
    if (auto o = r.vector(geo, "offset", d, "spacings", false)) {
      offset = to_vec(*o);
      for (int a = 0; a < d; ++a) {
        if (offset[a] < 0 || offset[a] >= 1) {
          r.error(YamlReader::child(geo, "offset"),
                  format_number(offset[a]) + " is out of range; allowed: [0, 1) spacings");
        }
      }
    }
  }
  const Field relax_f = YamlReader::child(geo, "relax");
  std::optional<g::RelaxOptions> relax_opt;
  if (YamlReader::present(relax_f) && r.expect_map(relax_f, kRelaxKeys)) {
    g::RelaxOptions ro;  // `relax: {}`: the defaults
    ro.tolerance = r.number_or(relax_f, "tolerance", 0.01, Bound::kPositive, "dimensionless");
    ro.max_iterations =
        static_cast<int>(r.integer(relax_f, "max_iterations", 1, 100000, false).value_or(400));
    relax_opt = ro;
  }
  if (!ctx.dimension_ok || !ctx.geometry_ok || d == 1) return;
  GeometryReader reader(ctx, d);
  const Field list = YamlReader::child(geo, "bodies");
  if (!YamlReader::present(list) || !list.node.IsSequence() || list.node.size() == 0) {
    r.error(list,
            "missing; required: a non-empty list of bodies, each {name, role: fluid | "
            "solid | region, shape}");
    return;
  }
  std::vector<BodyRead> bodies;
  std::set<std::string> names;
  for (const auto& rg : s.regions) names.insert(rg.name);
  auto claim = [&](const Field& where, const std::string& name) {
    if (!valid_identifier(name)) {
      r.error(where, "'" + name + "' is not a valid name; allowed: [A-Za-z_][A-Za-z0-9_]*");
    } else if (name == kAllRegion) {
      r.error(where, "'all' is the built-in region (every particle) and cannot be redefined");
    } else if (!names.insert(name).second) {
      r.error(where, "name '" + name +
                         "' is already used (a region or a body); region and body names must "
                         "be unique");
    }
  };
  const g::Aabb box = box_aabb(s.box);
  int fluid_bodies = 0;
  for (std::size_t i = 0; i < list.node.size(); ++i) {
    const Field f = YamlReader::element(list, i);
    if (!r.expect_map(f, kBodyKeys)) continue;
    BodyRead b;
    b.field = f;
    b.name = r.string(f, "name", true).value_or("");
    if (!b.name.empty()) claim(YamlReader::child(f, "name"), b.name);
    b.role = r.choice(f, "role", kRoles, true, "role").value_or("");
    if (b.role == "fluid" && ++fluid_bodies == 2) {
      r.error(YamlReader::child(f, "role"),
              "a second fluid body; allowed: one (join several with a shape of type 'union')");
    }
    b.shape_field = YamlReader::child(f, "shape");
    b.shape = reader.read_shape(b.shape_field, 0);
    if (b.shape.shape) {
      const g::Aabb bb = b.shape.shape->bounds();
      const g::Aabb both = g::intersect(bb, box);
      bool outside = false;
      for (int a = 0; a < d; ++a) outside = outside || !(both.lo[a] < both.hi[a]);
      if (outside) {
        r.error(b.shape_field,
                "the shape lies outside the box: its bounds " + point_text(bb.lo, d) + " to " +
                    point_text(bb.hi, d) + ", the box " + point_text(box.lo, d) + " to " +
                    point_text(box.hi, d) + "; allowed: a shape that overlaps the box");
      }
    }
    for (const auto* layer : {"wall_layer", "fluid_layer", "layer_thickness"}) {
      const Field lf = YamlReader::child(f, layer);
      if (YamlReader::present(lf) && b.role == "region") {
        r.error(lf, std::string("'") + layer +
                        "' applies to fluid and solid bodies (they have a surface with walls); "
                        "a region body has none");
      }
    }
    if (b.role != "region") {
      if (auto w = r.string(f, "wall_layer", false)) {
        b.wall_layer = *w;
        claim(YamlReader::child(f, "wall_layer"), *w);
      }
      if (auto w = r.string(f, "fluid_layer", false)) {
        b.fluid_layer = *w;
        claim(YamlReader::child(f, "fluid_layer"), *w);
      }
    }
    b.layer_thickness =
        r.number_or(f, "layer_thickness", dx.value_or(0.0), Bound::kPositive, "length");
    const Field kf = YamlReader::child(f, "kinds");
    if (YamlReader::present(kf) && b.role != "region") {
      r.error(kf,
              "'kinds' applies to region bodies only (a fluid body's region holds its fluid "
              "particles, a solid's its wall particles)");
    } else if (auto kinds = r.string_list(f, "kinds", false)) {
      for (const auto& k : *kinds) {
        if (auto kind = parse_kind(k)) {
          b.kinds.push_back(*kind);
        } else {
          std::string msg = "unknown particle kind '" + k + "'";
          if (auto near = nearest_name(k, kKindNames)) msg += "; did you mean '" + *near + "'?";
          r.error(kf, msg + " (allowed: " + join_names(kKindNames) + ")");
        }
      }
    }
    if (!b.shape.shape && r.diag().size() == errors_before) {  // every failure says why; in case
      r.error(b.shape_field,
              "the shape could not be made; required: a shape, e.g. {type: disk, "
              "center: [0.5, 0.5], radius: 0.1}");
    }
    b.surface_id = b.role == "region" ? -1 : static_cast<int>(i) + 1;
    bodies.push_back(std::move(b));
  }
  // Morris walls need their wall surfaces as planes or circles; geometry walls have none.
  if (s.fluid.wall_model == "morris" && s.fluid.wall_planes.empty()) {
    r.error(YamlReader::child(YamlReader::child(root, "fluid"), "wall_model"),
            "'morris' is not available for walls made by 'geometry' (their surfaces may be "
            "curved); allowed: 'stationary' (the default), or 'morris' with fluid.wall_planes "
            "naming a plane or circle per wall region");
  }
  if (!dx || !(h > 0) || r.diag().size() != errors_before) return;
  // Periodic axes: the lattice must tile the box.
  const double cell_x = lattice == g::Lattice::kCubic ? *dx
                        : d == 2                      ? *dx * std::sqrt(2.0 / std::sqrt(3.0))
                                                      : std::cbrt(4.0) * *dx;
  const double cell_y = lattice == g::Lattice::kCubic ? *dx
                        : d == 2                      ? cell_x * std::sqrt(3.0)
                                                      : cell_x;
  for (int a = 0; a < d; ++a) {
    if (!s.box.periodic[static_cast<std::size_t>(a)]) continue;
    const double c = a == 0 ? cell_x : a == 1 ? cell_y : cell_x;
    const double n = s.box.length(a) / c;
    if (std::abs(n - std::round(n)) > 1e-6 || std::round(n) < 1) {
      r.error(YamlReader::child(geo, "spacing"),
              format_number(*dx) + ": the " + lattice_name + " lattice's cell (" +
                  format_number(c) + " along " + "xyz"[a] +
                  ") does not tile the periodic box length " + format_number(s.box.length(a)) +
                  "; allowed: a spacing whose cell divides every periodic length");
    }
  }
  double sites = 1.0;
  for (int a = 0; a < d; ++a) sites *= s.box.length(a) / *dx;
  if (sites > kMaxSites) {
    r.error(YamlReader::child(geo, "spacing"),
            format_number(*dx) + " gives " + format_number(sites) +
                " lattice sites in the box; allowed: at most 5e7 (a coarser spacing)");
  }
  if (r.diag().size() != errors_before) return;

  g::FluidDomain dom;
  dom.dimension = d;
  dom.box = box;
  for (int a = 0; a < 3; ++a) dom.periodic[static_cast<std::size_t>(a)] = s.box.periodic[a];
  const ShapeRead* fluid_body = nullptr;
  std::map<int, g::ShapePtr> solids;
  for (const auto& b : bodies) {
    if (b.role == "fluid") {
      dom.body = b.shape.shape;
      dom.body_surface_id = b.surface_id;
      fluid_body = &b.shape;
    } else if (b.role == "solid") {
      dom.solids.push_back({b.shape.shape, b.surface_id});
      solids[b.surface_id] = b.shape.shape;
    }
  }
  const g::FillOptions fo{
      .spacing = *dx, .lattice = lattice, .wall_depth = wall_depth, .offset = offset};
  g::ParticleSet p;
  try {
    p = g::fill(dom, fo);
  } catch (const std::exception& e) {
    r.error(geo, e.what());
    return;
  }
  const std::size_t n_fluid = p.count(g::Kind::kFluid);
  if (n_fluid == 0) {
    r.error(list,
            "no lattice site lies in the fluid (inside the fluid body and outside every "
            "solid) at spacing " +
                format_number(*dx) +
                "; allowed: bodies that leave room for fluid, or a finer spacing");
    return;
  }
  for (const auto& b : bodies) {  // a solid the lattice misses would let the fluid through it
    if (b.role != "solid") continue;
    bool has_walls = false;
    for (std::size_t i = 0; i < p.size() && !has_walls; ++i) {
      has_walls = p.kind[i] == g::Kind::kWall && p.surface_id[i] == b.surface_id;
    }
    if (!has_walls) {
      r.error(b.shape_field, "solid '" + b.name + "' holds no wall particle at spacing " +
                                 format_number(*dx) +
                                 ": it is thinner than the lattice resolves (or lies inside "
                                 "another solid), and the fluid would flow through it; allowed: "
                                 "a solid at least a few spacings thick, or a finer spacing");
    }
  }
  if (r.diag().size() != errors_before) return;
  auto report = std::make_shared<GeometryReport>();
  report->lattice = lattice_name;
  report->spacing = *dx;
  report->wall_depth = wall_depth;
  report->notes = reader.notes();
  if (relax_opt) {
    relax_opt->support = h;
    try {
      const g::RelaxReport rr = g::relax(p, dom, lattice, *relax_opt);
      report->relaxed = true;
      report->relax_iterations = rr.iterations;
      report->max_error_before = rr.max_error_before;
      report->rms_error_before = rr.rms_error_before;
      report->max_error = rr.max_error;
      report->rms_error = rr.rms_error;
      const auto nd = g::number_density(p, dom, h);
      report->density_error.resize(p.size());
      for (std::size_t i = 0; i < p.size(); ++i) {
        report->density_error[i] = nd[i] / rr.reference_number_density - 1.0;
      }
      if (!(rr.max_error < relax_opt->tolerance)) {
        r.warning(relax_f, "relaxation stopped after " + std::to_string(rr.iterations) +
                               " iterations at a density error of " + format_number(rr.max_error) +
                               " (max), above the tolerance " +
                               format_number(relax_opt->tolerance) +
                               "; raise max_iterations or the tolerance");
      }
    } catch (const std::exception& e) {
      r.error(relax_f, e.what());
      return;
    }
  }
  const double cell_volume = std::pow(*dx, d);
  report->lattice_fluid_volume = static_cast<double>(n_fluid) * cell_volume;
  report->exact_fluid_volume = exact_fluid_volume(dom, fluid_body, s.box);
  const double volume = report->exact_fluid_volume.value_or(report->lattice_fluid_volume);
  g::assign_volumes(p, dom, h, volume, density);
  // Thin features: solids and fluid gaps thinner than the kernel support.
  report->feature_search = std::max(2.0 * h, 4.0 * *dx);
  const auto features = measure_features(p, dom, solids, h, report->feature_search);
  for (const auto& b : bodies) {
    if (b.surface_id < 0) continue;
    const auto it = features.find(b.surface_id);
    if (it == features.end()) continue;
    const auto& [solid, gap] = it->second;
    for (const Thin* th : {&solid, &gap}) {
      if (th->thickness < report->smallest_feature) {
        report->smallest_feature = th->thickness;
        report->smallest_feature_where = (th == &solid ? "solid '" : "fluid next to '") + b.name +
                                         "' near " + point_text(th->where, d);
      }
    }
    if (solid.count > 0) {
      r.warning(b.shape_field,
                "solid '" + b.name + "' is " + format_number(solid.thickness / *dx) +
                    " spacings thick near " + point_text(solid.where, d) +
                    ", thinner than the kernel support h = " + format_number(h / *dx) +
                    " spacings: fluid particles on its two sides interact through it; make it "
                    "at least h thick or use a finer spacing");
    }
    if (gap.count > 0) {
      r.warning(b.shape_field,
                "the fluid next to '" + b.name + "' is " + format_number(gap.thickness / *dx) +
                    " spacings across near " + point_text(gap.where, d) +
                    ", thinner than the kernel support h = " + format_number(h / *dx) +
                    " spacings: the gap is resolved by too few particles; use a finer spacing");
    }
  }

  // The particles.
  ParticleState& ps = s.particles;
  const std::size_t n = p.size();
  ps.dimension = d;
  ps.positions.resize(3 * n);
  ps.velocities.assign(3 * n, 0.0);
  ps.densities.assign(n, density);
  ps.masses.resize(n);
  ps.kinds.resize(n);
  ps.ids.resize(n);
  report->surface_id = p.surface_id;
  report->surface_distance = p.distance;
  for (std::size_t i = 0; i < n; ++i) {
    ps.positions[3 * i] = p.position[i].x;
    ps.positions[3 * i + 1] = p.position[i].y;
    ps.positions[3 * i + 2] = d == 3 ? p.position[i].z : 0.0;
    ps.masses[i] = p.mass[i];
    ps.kinds[i] = p.kind[i] == g::Kind::kWall ? ParticleKind::kWall : ParticleKind::kFluid;
    ps.ids[i] = i;
    if (p.kind[i] == g::Kind::kFluid) report->fluid_volume += p.volume[i];
  }
  // Regions: the scene's own, then each body's and its layers.
  resolve_regions(ctx, ps);
  const double tol = ctx.tolerance();
  for (const auto& b : bodies) {
    GeometryBody info;
    info.name = b.name;
    info.role = b.role;
    info.surface_id = b.surface_id;
    info.origin = r.diag().file() + ":" + std::to_string(b.field.where.line);
    info.exact_volume = b.shape.shape->exact_volume();
    if (b.shape.plain_box) {
      const g::Aabb bb = b.shape.shape->bounds();
      double v = 1;
      for (int a = 0; a < d; ++a) v *= bb.hi[a] - bb.lo[a];
      info.exact_volume = v;
    }
    report->bodies.push_back(info);
    std::vector<std::uint32_t> own, walls, fluid;
    for (std::size_t i = 0; i < n; ++i) {
      const auto ui = static_cast<std::uint32_t>(i);
      const bool wall = p.kind[i] == g::Kind::kWall;
      if (b.role == "region") {
        if (b.shape.shape->signed_distance(p.position[i]) <= tol) own.push_back(ui);
        continue;
      }
      const bool mine = p.surface_id[i] == b.surface_id;
      if (b.role == "fluid" ? !wall : (wall && mine)) own.push_back(ui);
      if (mine && wall && p.distance[i] < b.layer_thickness) walls.push_back(ui);
      if (mine && !wall && p.distance[i] < b.layer_thickness) fluid.push_back(ui);
    }
    add_region(ctx, b.name, std::move(own), b.kinds);
    if (!b.wall_layer.empty()) add_region(ctx, b.wall_layer, std::move(walls), {});
    if (!b.fluid_layer.empty()) add_region(ctx, b.fluid_layer, std::move(fluid), {});
    if (!b.wall_layer.empty() && s.find_region(b.wall_layer)->particles.empty()) {
      r.warning(YamlReader::child(b.field, "wall_layer"),
                "region '" + b.wall_layer + "' holds no particle (no wall within " +
                    format_number(b.layer_thickness) + " behind the surface of '" + b.name + "')");
    }
  }
  s.geometry = std::move(report);
  ctx.particles_ok = r.diag().size() == errors_before;
}

}  // namespace detail

GeometryDensityError geometry_density_error(const Scene& scene) {
  namespace g = sadr::geometry;
  if (!scene.geometry) {
    throw InvalidArgument("the scene's particles do not come from a 'geometry' section");
  }
  const GeometryReport& rep = *scene.geometry;
  const ParticleState& ps = scene.particles;
  const int d = scene.box.dimension;
  GeometryDensityError out;
  const std::size_t n = ps.size();
  if (rep.density_error.size() == n) {
    out.per_particle = rep.density_error;
  } else {
    g::ParticleSet p;
    p.dimension = d;
    p.spacing = rep.spacing;
    for (std::size_t i = 0; i < n; ++i) {
      p.position.push_back({ps.positions[3 * i], ps.positions[3 * i + 1], ps.positions[3 * i + 2]});
      p.kind.push_back(ps.kinds[i] == ParticleKind::kWall ? g::Kind::kWall : g::Kind::kFluid);
    }
    p.surface_id = rep.surface_id;
    p.distance = rep.surface_distance;
    p.normal.assign(n, g::Vec3{});
    p.volume.assign(n, 0.0);
    p.mass.assign(n, 0.0);
    g::FluidDomain dom;
    dom.dimension = d;
    dom.box = {{scene.box.lo[0], scene.box.lo[1], scene.box.lo[2]},
               {scene.box.hi[0], scene.box.hi[1], scene.box.hi[2]}};
    for (int a = 0; a < 3; ++a) dom.periodic[static_cast<std::size_t>(a)] = scene.box.periodic[a];
    const double h = scene.fluid.smoothing_length;
    const auto nd = g::number_density(p, dom, h);
    const double n0 = g::reference_number_density(
        d, rep.lattice == "hexagonal" ? g::Lattice::kHexagonal : g::Lattice::kCubic, rep.spacing,
        h);
    out.per_particle.resize(n);
    for (std::size_t i = 0; i < n; ++i) out.per_particle[i] = nd[i] / n0 - 1.0;
  }
  double sum2 = 0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (ps.kinds[i] != ParticleKind::kFluid) continue;
    const double e = std::abs(out.per_particle[i]);
    out.max = std::max(out.max, e);
    sum2 += e * e;
    ++count;
  }
  out.rms = count ? std::sqrt(sum2 / static_cast<double>(count)) : 0.0;
  return out;
}

}  // namespace sadr::orchestrator
