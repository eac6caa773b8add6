// SPDX-License-Identifier: MIT
// Scene section "geometry": the shapes of its bodies as the scene gives them (primitives, mesh
// files, transforms, CSG to any depth), read and checked with file:line errors.
#include <cmath>
#include <cstdio>
#include <numbers>

#include "sadr/common/status.hpp"
#include "sadr/geometry/mesh.hpp"
#include "sadr/orchestrator/hash.hpp"
#include "scene_geometry_parts.hpp"

namespace sadr::orchestrator::detail {

namespace {

constexpr std::array<std::string_view, 18> kShapeKeys{
    "type",   "lower", "upper",        "center",       "radius",   "radii",
    "start",  "end",   "major_radius", "minor_radius", "vertices", "z",
    "shapes", "file",  "group",        "translate",    "rotate",   "scale"};
constexpr std::array<std::string_view, 2> kRotateKeys{"axis", "angle"};
constexpr std::array<std::string_view, 14> kShapeTypes{
    "box",   "sphere",  "disk",      "ellipsoid", "ellipse",      "cylinder",   "capsule",
    "torus", "polygon", "extrusion", "union",     "intersection", "difference", "mesh"};
constexpr int kMaxDepth = 32;

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
}  // namespace

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

g::Aabb box_aabb(const Box& b) {
  return {{b.lo[0], b.lo[1], b.lo[2]}, {b.hi[0], b.hi[1], b.hi[2]}};
}

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
      it = meshes_.emplace(key, std::make_shared<const g::MeshFile>(g::read_mesh(key, d_))).first;
      // A changed mesh is a changed scene (checkpoints refuse it): its hash joins the scene's.
      ctx_.particle_file_bytes += "\nmesh " + file_hash(key);
    } catch (const std::exception& e) {
      r_.error(file, std::string(e.what()) +
                         " (mesh files: .stl or .msh, paths relative to the scene file's "
                         "directory)");
      return out;
    }
  }
  const g::MeshFile& mf = *it->second;
  out.mesh_file = it->second;
  out.mesh_path = key;
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
    if (s.mesh_file) {
      s.place = [prev = s.place, factors](g::ShapePtr x) {
        return g::scale(prev ? prev(std::move(x)) : std::move(x), factors);
      };
    }
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
    const double radians = *angle * std::numbers::pi / 180.0;
    s.shape = g::rotate(s.shape, axis, radians);
    s.plain_box = false;
    if (s.mesh_file) {
      s.place = [prev = s.place, axis, radians](g::ShapePtr x) {
        return g::rotate(prev ? prev(std::move(x)) : std::move(x), axis, radians);
      };
    }
  }
  if (YamlReader::present(YamlReader::child(f, "translate"))) {
    const auto t = r_.vector(f, "translate", d_, "length", true);
    if (!t) return {};
    s.shape = g::translate(s.shape, to_vec(*t));
    if (s.mesh_file) {
      s.place = [prev = s.place, offset = to_vec(*t)](g::ShapePtr x) {
        return g::translate(prev ? prev(std::move(x)) : std::move(x), offset);
      };
    }
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
}  // namespace sadr::orchestrator::detail
