// SPDX-License-Identifier: MIT
// Scene section "fluid": backend name and its parameters, validated from the backend schema
// (sadr/fluid/backend_schema.hpp): no backend name is spelled here.
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>

#include "sadr/common/input_file.hpp"
#include "sadr/common/status.hpp"
#include "sadr/fluid/backend_schema.hpp"
#include "scene_parts.hpp"

namespace sadr::orchestrator::detail {

namespace {
constexpr std::array<std::string_view, 18> kFluidKeys{
    "backend",     "smoothing_length", "h_over_dx",       "kernel",     "reference_density",
    "sound_speed", "shear_viscosity",  "temperature",     "gravity",    "density_mode",
    "boussinesq",  "max_time_step",    "force_time_step", "parameters", "open_boundary",
    "wall_model",  "wall_planes",      "body_forces"};
constexpr std::array<std::string_view, 5> kPlaneKeys{"region", "point", "normal", "center",
                                                     "radius"};
constexpr std::array<std::string_view, 8> kOpenKeys{
    "axis", "inlet", "outlet", "profile", "mean_velocity", "max_velocity", "walls", "cross_axis"};
constexpr std::array<std::string_view, 3> kAxes{"x", "y", "z"};
constexpr std::array<std::string_view, 2> kProfiles{"uniform", "parabolic"};
constexpr std::string_view kOpenPrefix = "open_boundary.";
constexpr std::array<std::string_view, 2> kDensityModes{"continuity", "summation"};
constexpr std::array<std::string_view, 4> kBoussinesqKeys{"species", "coefficient", "reference",
                                                          "direction"};

void read_boussinesq(SceneContext& ctx, const Field& fluid) {
  YamlReader& r = ctx.reader;
  const Field b = YamlReader::child(fluid, "boussinesq");
  if (!YamlReader::present(b) || !r.expect_map(b, kBoussinesqKeys)) return;
  Boussinesq out;
  out.species = r.string(b, "species", true).value_or("");
  out.coefficient =
      r.number(b, "coefficient", Bound::kAny, "length^(d+2)/(time^2 molecules)", true).value_or(0);
  out.reference = r.number_or(b, "reference", 0.0, Bound::kNonNegative, "molecules/length^d");
  const int d = ctx.scene.box.dimension;
  if (d == 1) out.direction = {1.0, 0.0, 0.0};
  if (auto dir =
          ctx.dimension_ok ? r.vector(b, "direction", d, "dimensionless", false) : std::nullopt) {
    const double norm =
        std::sqrt((*dir)[0] * (*dir)[0] + (*dir)[1] * (*dir)[1] + (*dir)[2] * (*dir)[2]);
    if (!(norm > 0.0)) {
      r.error(YamlReader::child(b, "direction"),
              "the zero vector is not allowed; allowed: a "
              "non-zero vector (it is normalised)");
    } else {
      for (auto& c : *dir) c /= norm;
      out.direction = *dir;
    }
  }
  ctx.scene.fluid.boussinesq = out;
  ctx.boussinesq = b;
}

/// A number for messages (as a scene would write it, not 17 digits).
int axis_index(std::string_view name) {
  return name == "x" ? 0 : name == "y" ? 1 : 2;
}

namespace schema = sadr::fluid::schema;

std::vector<std::string_view> views(const std::vector<std::string>& v) {
  return {v.begin(), v.end()};
}

/// "backend sdpd" / "backends a, b": the backends with a capability, for "allowed:" messages.
std::string backends_with(bool (*has)(const schema::Backend&)) {
  std::vector<std::string> names;
  for (const auto& b : schema::backends()) {
    if (has(b)) names.push_back(b.name);
  }
  std::string s = names.size() == 1 ? "backend " : "backends ";
  for (std::size_t i = 0; i < names.size(); ++i) s += (i ? ", " : "") + names[i];
  return s;
}

/// fluid.wall_planes: [{region, point, normal}] (a plane) or [{region, center, radius}] (a
/// circle in 2D, a sphere in 3D, the fluid outside), only (and at least one, unless the walls
/// come from a `geometry` section) with wall_model morris. The region names are checked once the
/// regions are read (check_wall_planes).
void read_wall_planes(SceneContext& ctx, const Field& f, bool geometry) {
  YamlReader& r = ctx.reader;
  FluidSettings& fl = ctx.scene.fluid;
  const Field planes = YamlReader::child(f, "wall_planes");
  const bool morris = fl.wall_model == "morris";
  if (!YamlReader::present(planes)) {
    if (morris && !geometry) {  // walls made by geometry carry their own tangent planes
      r.error(planes,
              "missing; wall_model morris needs the wall surface of each wall region: "
              "[{region, point, normal}] or [{region, center, radius}] (docs/scene-format.md)");
    }
    return;
  }
  if (!morris) {
    r.error(planes, "only with wall_model: morris (the wall model here is " + fl.wall_model + ")");
    return;
  }
  if (!r.expect_sequence(planes) || !ctx.dimension_ok) return;
  const int d = ctx.scene.box.dimension;
  for (std::size_t i = 0; i < planes.node.size(); ++i) {
    const Field e = YamlReader::element(planes, i);
    if (!r.expect_map(e, kPlaneKeys)) continue;
    WallPlane p;
    const auto region = r.string(e, "region", true);
    if (YamlReader::present(YamlReader::child(e, "radius"))) {
      // A curved surface: a circle (sphere) around center, the wall inside it.
      for (const char* k : {"point", "normal"}) {
        const Field extra = YamlReader::child(e, k);
        if (YamlReader::present(extra)) {
          r.error(extra,
                  "not with radius (a surface is {region, point, normal}, a plane, or "
                  "{region, center, radius}, a circle or sphere)");
        }
      }
      const auto center = r.vector(e, "center", d, "length", true);
      const auto radius = r.number(e, "radius", Bound::kPositive, "length", true);
      if (!region || !center || !radius) continue;
      p.region = *region;
      p.point = *center;
      p.radius = *radius;
      fl.wall_planes.push_back(std::move(p));
      continue;
    }
    if (const Field c = YamlReader::child(e, "center"); YamlReader::present(c)) {
      r.error(c, "only with radius (a circle or sphere: {region, center, radius})");
    }
    const auto point = r.vector(e, "point", d, "length", true);
    const auto normal = r.vector(e, "normal", d, "dimensionless", true);
    if (!region || !point || !normal) continue;
    const double len = std::sqrt((*normal)[0] * (*normal)[0] + (*normal)[1] * (*normal)[1] +
                                 (*normal)[2] * (*normal)[2]);
    if (!(len > 0)) {
      r.error(YamlReader::child(e, "normal"), "must be non-zero (it points into the fluid)");
      continue;
    }
    p.region = *region;
    p.point = *point;
    for (int a = 0; a < 3; ++a) p.normal[a] = (*normal)[a] / len;
    fl.wall_planes.push_back(std::move(p));
  }
}

/// fluid.parameters against the backend's parameter schema (name and range).
void read_parameters(SceneContext& ctx, const Field& f, const schema::Backend* backend) {
  YamlReader& r = ctx.reader;
  const Field params = YamlReader::child(f, "parameters");
  if (!YamlReader::present(params)) return;
  if (!params.node.IsMap()) {
    r.error(params, "expected a map of name: number (backend-specific parameters)");
    return;
  }
  for (const auto& kv : params.node) {
    const std::string key = kv.first.Scalar();
    if (key.rfind(kOpenPrefix, 0) == 0) {
      r.error(YamlReader::child(params, key),
              "reserved name; allowed: the map fluid.open_boundary (docs/scene-format.md)");
      continue;
    }
    const schema::Parameter* spec = backend ? backend->parameter(key) : nullptr;
    if (backend && !spec) {
      std::string known;
      for (const auto& p : backend->parameters) known += (known.empty() ? "" : ", ") + p.name;
      r.error(YamlReader::child(params, key),
              "unknown parameter of backend '" + backend->name + "'; allowed: " +
                  (known.empty() ? std::string("none") : known) + " (sadr backends)");
      continue;
    }
    if (spec && spec->file) {  // a path, relative to the scene file; the backend reads it
      const Field at = YamlReader::child(params, key);
      const auto name = r.string(params, key, true);
      if (!name) continue;
      std::filesystem::path path(*name);
      if (path.is_relative()) path = ctx.base_dir / path;
      std::error_code ec;
      path = std::filesystem::absolute(path, ec).lexically_normal();
      if (!std::ifstream(path)) {
        r.error(at, "cannot open '" + path.string() +
                        "'; allowed: a readable file (paths are relative to the scene file)");
        continue;
      }
      try {
        require_regular_file(path, kMaxDataFileBytes, "file");
      } catch (const InvalidArgument& e) {
        r.error(at, std::string(e.what()) + " (paths are relative to the scene file)");
        continue;
      }
      ctx.scene.fluid.files[key] = path.string();
      continue;
    }
    if (spec && !spec->choices.empty()) {  // a name; the wire carries its index
      std::vector<std::string_view> names(spec->choices.begin(), spec->choices.end());
      const auto name = r.choice(params, key, names, true, "name");
      if (name) ctx.scene.fluid.parameters[key] = spec->choice_index(*name);
      continue;
    }
    const auto v = r.number(params, key, Bound::kAny, spec ? spec->unit : "", true);
    std::string why;
    if (v && spec && !spec->allows(*v, why)) {
      r.error(YamlReader::child(params, key), format_short(*v) +
                                                  " is out of range; allowed: " + why + " [" +
                                                  spec->unit + "] (" + spec->doc + ")");
      continue;
    }
    if (v) ctx.scene.fluid.parameters[key] = *v;
  }
}

/// fluid.open_boundary -> FluidSettings::open_boundary (sent as the typed
/// FluidModel.open_boundary).
void read_open_boundary(SceneContext& ctx, const Field& fluid, bool allowed) {
  YamlReader& r = ctx.reader;
  const Field ob = YamlReader::child(fluid, "open_boundary");
  if (!YamlReader::present(ob) || !r.expect_map(ob, kOpenKeys)) return;
  const auto backend = ctx.scene.fluid.backend;
  if (!allowed) {
    r.error(ob, std::string("backend '") + backend + "' has no open boundaries; allowed: " +
                    backends_with(
                        [](const schema::Backend& b) { return b.capabilities.open_boundaries; }) +
                    " (or remove open_boundary)");
  }
  if (!ctx.dimension_ok) return;
  const int d = ctx.scene.box.dimension;
  OpenBoundarySettings& p = ctx.scene.fluid.open_boundary.emplace();
  const std::span<const std::string_view> axes(kAxes.data(), static_cast<std::size_t>(d));
  int axis = 0;
  if (auto a = r.choice(ob, "axis", axes, false, "axis")) axis = axis_index(*a);
  if (ctx.geometry_ok && ctx.scene.box.periodic[static_cast<std::size_t>(axis)]) {
    r.error(YamlReader::child(ob, "axis"),
            "box.periodic is true along the flow axis; allowed: a "
            "walled (non-periodic) axis");
  }
  p.axis = axis;
  const auto in = r.vector(ob, "inlet", 2, "length", true);
  const auto out = r.vector(ob, "outlet", 2, "length", true);
  if (in && out) {
    const double lo = ctx.scene.box.lo[static_cast<std::size_t>(axis)];
    const double hi = ctx.scene.box.hi[static_cast<std::size_t>(axis)];
    if (!((*in)[0] < (*in)[1] && (*in)[1] < (*out)[0] && (*out)[0] < (*out)[1])) {
      r.error(YamlReader::child(ob, "outlet"),
              std::string("inlet [") + format_short((*in)[0]) + ", " + format_short((*in)[1]) +
                  "], outlet [" + format_short((*out)[0]) + ", " + format_short((*out)[1]) +
                  "]; allowed: inlet = [x0 - Lb, x0], outlet = [x1, x1 + Lb'] with x0 < x1 (the "
                  "fluid part [x0, x1] between them) and lengths > 0");
    } else if (ctx.geometry_ok &&
               ((*in)[0] < lo - ctx.tolerance() || (*out)[1] > hi + ctx.tolerance())) {
      r.error(YamlReader::child(ob, "inlet"),
              std::string("the channel [") + format_short((*in)[0]) + ", " +
                  format_short((*out)[1]) + "] leaves the box [" + format_short(lo) + ", " +
                  format_short(hi) + "] along the flow axis; allowed: inside the box");
    }
    p.inlet_lo = (*in)[0];
    p.fluid_lo = (*in)[1];
    p.fluid_hi = (*out)[0];
    p.outlet_hi = (*out)[1];
    ctx.open_boundary = ob;  // the channel is known: check_open_boundary checks it against h
  }
  const std::string profile =
      r.choice(ob, "profile", kProfiles, false, "profile").value_or("uniform");
  const bool parabolic = profile == "parabolic";
  p.parabolic = parabolic;
  const auto mean = r.number(ob, "mean_velocity", Bound::kPositive, "length/time", false);
  const auto max = r.number(ob, "max_velocity", Bound::kPositive, "length/time", false);
  const bool mean_given = YamlReader::present(YamlReader::child(ob, "mean_velocity"));
  const bool max_given = YamlReader::present(YamlReader::child(ob, "max_velocity"));
  if (mean_given && max_given) {
    r.error(YamlReader::child(ob, "max_velocity"),
            "give either mean_velocity or max_velocity, not both");
  } else if (!mean_given && !max_given) {
    r.error(YamlReader::child(ob, "mean_velocity"),
            "missing; required: mean_velocity or max_velocity (a number > 0 [length/time])");
  }
  if (mean) p.mean_velocity = *mean;
  if (max && !mean_given) p.mean_velocity = parabolic ? *max / 1.5 : *max;
  const Field walls = YamlReader::child(ob, "walls");
  const Field cross = YamlReader::child(ob, "cross_axis");
  if (!parabolic) {
    if (YamlReader::present(walls)) r.error(walls, "applies to profile: parabolic only");
    if (YamlReader::present(cross)) r.error(cross, "applies to profile: parabolic only");
    return;
  }
  if (d == 1) {
    r.error(YamlReader::child(ob, "profile"),
            "'parabolic' needs a cross axis; allowed in 1D: uniform");
    return;
  }
  int ca = axis == 0 ? 1 : 0;
  if (auto c = r.choice(ob, "cross_axis", axes, false, "axis")) {
    ca = axis_index(*c);
    if (ca == axis) r.error(cross, "equals the flow axis; allowed: another active axis");
  }
  p.cross_axis = ca;
  if (auto w = r.vector(ob, "walls", 2, "length", true)) {
    if (!((*w)[0] < (*w)[1])) {
      r.error(walls, std::string("[") + format_short((*w)[0]) + ", " + format_short((*w)[1]) +
                         "]; allowed: [lo, hi] with lo < hi (the no-slip planes where the "
                         "parabola is zero)");
    }
    p.wall_lo = (*w)[0];
    p.wall_hi = (*w)[1];
  }
}

}  // namespace

void check_wall_planes(SceneContext& ctx, const Field& root) {
  const Field planes = YamlReader::child(YamlReader::child(root, "fluid"), "wall_planes");
  const auto& list = ctx.scene.fluid.wall_planes;
  for (std::size_t i = 0; i < list.size() && i < planes.node.size(); ++i) {
    if (ctx.scene.find_region(list[i].region)) continue;
    std::string known;
    for (const auto& reg : ctx.scene.regions) known += (known.empty() ? "" : ", ") + reg.name;
    ctx.reader.error(YamlReader::child(YamlReader::element(planes, i), "region"),
                     "unknown region '" + list[i].region + "' (allowed: " +
                         (known.empty() ? std::string("none defined") : known) + ")");
  }
}

void check_open_boundary(SceneContext& ctx) {
  if (!ctx.open_boundary || !ctx.particles_ok) return;
  YamlReader& r = ctx.reader;
  const Field ob = *ctx.open_boundary;
  const OpenBoundarySettings& p = *ctx.scene.fluid.open_boundary;
  const double in_lo = p.inlet_lo, x0 = p.fluid_lo, x1 = p.fluid_hi, out_hi = p.outlet_hi;
  const double h = ctx.scene.fluid.smoothing_length;
  if (h > 0 && x0 - in_lo < h * (1 - 1e-9)) {
    r.error(YamlReader::child(ob, "inlet"),
            std::string("length ") + format_short(x0 - in_lo) +
                " is shorter than the kernel support h = " + format_short(h) +
                "; allowed: a length >= h (fluid near the inlet needs a full "
                "kernel of buffer particles)");
  }
  if (h > 0 && out_hi - x1 < h * (1 - 1e-9)) {
    r.error(YamlReader::child(ob, "outlet"), std::string("length ") + format_short(out_hi - x1) +
                                                 " is shorter than the kernel support h = " +
                                                 format_short(h) + "; allowed: a length >= h");
  }
  const double dx = ctx.scene.lattice_spacing;
  if (dx > 0) {  // the inlet conveyor's slots repeat with the inlet length
    const double k = (x0 - in_lo) / dx;
    if (std::fabs(k - std::round(k)) > 1e-6 * std::max(1.0, k)) {
      r.error(YamlReader::child(ob, "inlet"),
              std::string("length ") + format_short(x0 - in_lo) + " is not a whole number of " +
                  "particles.spacing = " + format_short(dx) +
                  "; allowed: k * spacing (the inlet's k lattice columns are the slots of the "
                  "inflow conveyor)");
    }
  }
  const auto& s = ctx.scene.particles;
  const auto a = static_cast<std::size_t>(p.axis);
  const double tol = ctx.tolerance();
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s.kind(i) == ParticleKind::kWall) continue;
    const double xa = s.positions[3 * i + a];
    if (xa < in_lo - tol || xa > out_hi + tol) {
      r.error(YamlReader::child(ob, "inlet"),
              std::string("particle ") + std::to_string(i) + " (kind " +
                  std::string(to_string(s.kind(i))) + ") at " + format_short(xa) +
                  " along the flow axis lies outside the channel [" + format_short(in_lo) + ", " +
                  format_short(out_hi) +
                  "]; allowed: only wall particles outside the inlet and outlet buffers");
      return;
    }
  }
}

void read_fluid(SceneContext& ctx, const Field& root) {
  YamlReader& r = ctx.reader;
  FluidSettings& fl = ctx.scene.fluid;
  const Field f = YamlReader::child(root, "fluid");
  if (!YamlReader::present(f)) {
    r.error(f, "missing; required: a map with at least 'backend' and the smoothing length");
    return;
  }
  if (!r.expect_map(f, kFluidKeys)) return;
  std::vector<std::string> names;
  for (const auto& b : schema::backends()) names.push_back(b.name);
  const auto known = views(names);
  const auto backend = r.choice(f, "backend", known, true, "fluid backend");
  if (backend) fl.backend = *backend;
  // (an unknown backend: no follow-up errors)
  const schema::Backend* spec = backend ? schema::find(*backend) : nullptr;
  auto required = [&](std::string_view key) { return spec && spec->needs(key); };
  const auto h = r.number(f, "smoothing_length", Bound::kPositive, "length", false);
  ctx.h_over_dx = r.number(f, "h_over_dx", Bound::kPositive, "dimensionless", false);
  if (h && ctx.h_over_dx) {
    r.error(YamlReader::child(f, "h_over_dx"),
            "give either smoothing_length or h_over_dx, not both");
    ctx.h_over_dx.reset();
  }
  if (h) fl.smoothing_length = *h;
  if (!h && !ctx.h_over_dx && !YamlReader::present(YamlReader::child(f, "smoothing_length")) &&
      !YamlReader::present(YamlReader::child(f, "h_over_dx"))) {
    r.error(YamlReader::child(f, "smoothing_length"),
            "missing; required: smoothing_length (a number > 0 [length]) or h_over_dx (> 0)");
  }
  if (spec) {  // the backend's kernels, its first the default
    const auto kernels = views(spec->capabilities.kernels);
    fl.kernel = spec->capabilities.kernels.front();
    if (auto k = r.choice(f, "kernel", kernels, false, "kernel")) fl.kernel = *k;
  }
  fl.reference_density =
      r.number_or(f, "reference_density", 1.0, Bound::kPositive, "mass/length^d");
  fl.sound_speed = r.number(f, "sound_speed", Bound::kPositive, "length/time", false).value_or(0);
  fl.shear_viscosity = r.number(f, "shear_viscosity", Bound::kNonNegative,
                                "mass/(length^(d-2) time)", required("shear_viscosity"))
                           .value_or(0);
  fl.temperature = r.number_or(f, "temperature", 0.0, Bound::kNonNegative, "energy");
  if (ctx.dimension_ok) {
    if (auto g = r.vector(f, "gravity", ctx.scene.box.dimension, "length/time^2", false)) {
      fl.gravity = *g;
    }
  }
  if (auto m = r.choice(f, "density_mode", kDensityModes, false, "density mode")) {
    fl.density_mode = *m;
  }
  fl.max_time_step = r.number_or(f, "max_time_step", 0.0, Bound::kNonNegative, "time");
  fl.force_time_step = r.boolean(f, "force_time_step", false).value_or(false);
  if (spec) {  // the backend's wall models, its first the default
    const auto models = views(spec->capabilities.wall_models);
    fl.wall_model = spec->capabilities.wall_models.front();
    if (auto w = r.choice(f, "wall_model", models, false, "wall model")) fl.wall_model = *w;
  }
  if (spec) read_wall_planes(ctx, f, YamlReader::present(YamlReader::child(root, "geometry")));
  read_parameters(ctx, f, spec);
  read_boussinesq(ctx, f);
  read_open_boundary(ctx, f, !spec || spec->capabilities.open_boundaries);
}

}  // namespace sadr::orchestrator::detail
