// SPDX-License-Identifier: MIT
// Scene section "geometry": particles from bodies (shapes, CSG, meshes) through the geometry
// library (docs/geometry.md): a fluid domain, solid bodies with wall layers, named regions and
// surface layers; instead of the section "particles".
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <set>

#include "sadr/common/status.hpp"
#include "sadr/orchestrator/hash.hpp"
#include "sadr/orchestrator/scene_geometry.hpp"
#include "scene_geometry_parts.hpp"

namespace sadr::orchestrator {
namespace detail {

namespace {

constexpr std::array<std::string_view, 7> kGeometryKeys{
    "spacing", "lattice", "density", "wall_depth", "offset", "relax", "bodies"};
constexpr std::array<std::string_view, 8> kBodyKeys{
    "name", "role", "shape", "wall_layer", "fluid_layer", "layer_thickness", "kinds", "motion"};
constexpr std::array<std::string_view, 2> kRelaxKeys{"tolerance", "max_iterations"};
constexpr std::array<std::string_view, 3> kRoles{"fluid", "solid", "region"};
constexpr std::array<std::string_view, 2> kLattices{"cubic", "hexagonal"};
constexpr std::array<std::string_view, 4> kGeometryKinds{"fluid", "wall", "inlet", "outlet"};
constexpr double kMaxSites = 5e7;

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
          if (auto near = nearest_name(k, kGeometryKinds)) msg += "; did you mean '" + *near + "'?";
          r.error(kf, msg + " (allowed: " + join_names(kGeometryKinds) + ")");
        }
      }
    }
    if (!b.shape.shape && r.diag().size() == errors_before) {  // every failure says why; in case
      r.error(b.shape_field,
              "the shape could not be made; required: a shape, e.g. {type: disk, "
              "center: [0.5, 0.5], radius: 0.1}");
    }
    b.surface_id = b.role == "region" ? -1 : static_cast<int>(i) + 1;
    if (const Field mf = YamlReader::child(f, "motion"); YamlReader::present(mf)) {
      if (b.role == "solid") {
        b.motion = read_wall_motion(ctx, f);
      } else {
        r.error(mf, "'motion' applies to solid bodies (their wall particles move)");
      }
    }
    bodies.push_back(std::move(b));
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
  report->surface_normal.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    ps.positions[3 * i] = p.position[i].x;
    ps.positions[3 * i + 1] = p.position[i].y;
    ps.positions[3 * i + 2] = d == 3 ? p.position[i].z : 0.0;
    ps.masses[i] = p.mass[i];
    ps.kinds[i] = p.kind[i] == g::Kind::kWall ? ParticleKind::kWall : ParticleKind::kFluid;
    ps.ids[i] = i;
    report->surface_normal[i] = {p.normal[i].x, p.normal[i].y, p.normal[i].z};
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
    if (b.motion && b.motion->moves) info.moving = b.motion->rigid();
    info.origin = r.diag().file() + ":" + std::to_string(b.field.where.line);
    info.exact_volume = b.shape.shape->exact_volume();
    info.exact_area = b.shape.shape->exact_area();
    const g::Aabb sb = b.shape.shape->bounds();
    info.inside_box = true;
    for (int a = 0; a < d; ++a) {
      info.inside_box = info.inside_box && sb.lo[a] > box.lo[a] && sb.hi[a] < box.hi[a];
    }
    if (b.shape.plain_box) {
      const g::Aabb bb = b.shape.shape->bounds();
      double v = 1;
      for (int a = 0; a < d; ++a) v *= bb.hi[a] - bb.lo[a];
      info.exact_volume = v;
    }
    report->bodies.push_back(info);
    if (b.shape.mesh_file && b.role != "region") {
      ctx.mesh_bodies[b.name] = std::make_shared<const MeshBody>(
          MeshBody{b.shape.mesh_file, b.shape.mesh_path, b.shape.place, b.shape.shape});
    }
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
    if (b.motion) {
      apply_body_motion(ctx, YamlReader::child(b.field, "motion"), *b.motion, own,
                        report->surface_normal);
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