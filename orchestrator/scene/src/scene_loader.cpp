// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/scene_loader.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "sadr/common/input_file.hpp"
#include "sadr/common/status.hpp"
#include "sadr/fluid/backend_schema.hpp"
#include "sadr/orchestrator/hash.hpp"
#include "scene_override_tree.hpp"
#include "scene_parts.hpp"

namespace sadr::orchestrator {

namespace detail {

double SceneContext::tolerance() const {
  double extent = 0.0;
  for (int a = 0; a < scene.box.dimension; ++a) extent = std::max(extent, scene.box.length(a));
  return 1e-9 * std::max(extent, 1e-300);
}

std::optional<ParticleKind> parse_kind(std::string_view name) {
  if (name == "fluid") return ParticleKind::kFluid;
  if (name == "wall") return ParticleKind::kWall;
  if (name == "inlet") return ParticleKind::kInlet;
  if (name == "outlet") return ParticleKind::kOutlet;
  return std::nullopt;
}

bool valid_identifier(std::string_view name) {
  if (name.empty()) return false;
  auto alpha = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; };
  if (!alpha(name[0])) return false;
  return std::all_of(name.begin(), name.end(),
                     [&](char c) { return alpha(c) || (c >= '0' && c <= '9'); });
}

std::optional<std::string> invalid_scene_name(std::string_view name) {
  // The name becomes <output>/<name>.pvd and runs/<name>-<time>: a file name,
  // never a path (no '/', no leading '.', no "..").
  constexpr std::size_t kMaxLength = 128;
  const std::string shown =
      name.size() > 40 ? std::string(name.substr(0, 40)) + "..." : std::string(name);
  if (name.empty()) return "the scene name is empty; allowed: 1-128 characters [A-Za-z0-9_.-]";
  if (name.size() > kMaxLength) {
    return "'" + shown + "' has " + std::to_string(name.size()) +
           " characters; allowed: at most 128 (it names the output files)";
  }
  const bool chars_ok = std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-' || c == '.';
  });
  if (!chars_ok || name.front() == '.' || name.front() == '-') {
    return "'" + shown +
           "' is not a valid scene name (it names the output files); allowed: "
           "[A-Za-z0-9_][A-Za-z0-9_.-]*, no '/' or leading '.'";
  }
  return std::nullopt;
}

std::string scene_name_from_file(const std::filesystem::path& source) {
  std::string name = source.stem().string().substr(0, 128);
  for (char& c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '-' || c == '.';
    if (!ok) c = '_';
  }
  if (name.empty() || name.front() == '.' || name.front() == '-') name.insert(0, "scene");
  return name;
}

namespace {

constexpr std::array<std::string_view, 16> kTopKeys{
    "name",   "description", "dimension", "box",       "regions",         "particles",
    "fluid",  "parameters",  "species",   "reactions", "boundary_fluxes", "time",
    "output", "seed",        "ssa",       "geometry"};

void read_box(SceneContext& ctx, const Field& root) {
  YamlReader& r = ctx.reader;
  Scene& s = ctx.scene;
  const auto dim = r.integer(root, "dimension", 1, 3, true);
  if (dim) {
    ctx.dimension_ok = true;
    s.box.dimension = static_cast<int>(*dim);
    s.particles.dimension = s.box.dimension;
  }
  const Field box = YamlReader::child(root, "box");
  if (!YamlReader::present(box)) {
    r.error(box, "missing; required: a map with lower, upper and optional periodic");
    return;
  }
  static constexpr std::array<std::string_view, 3> kKeys{"lower", "upper", "periodic"};
  if (!r.expect_map(box, kKeys) || !dim) return;
  const int d = static_cast<int>(*dim);
  const auto lo = r.vector(box, "lower", d, "length", true);
  const auto hi = r.vector(box, "upper", d, "length", true);
  const Field per = YamlReader::child(box, "periodic");
  bool ok = lo && hi;
  if (YamlReader::present(per)) {
    if (!per.node.IsSequence() || per.node.size() != static_cast<std::size_t>(d)) {
      r.error(per, "expected a list of " + std::to_string(d) + " true/false values (one per axis)");
      ok = false;
    } else {
      for (int a = 0; a < d; ++a) {
        const Field e = YamlReader::element(per, static_cast<std::size_t>(a));
        const std::string& t = e.node.IsScalar() ? e.node.Scalar() : std::string();
        if (t == "true" || t == "false") {
          s.box.periodic[static_cast<std::size_t>(a)] = t == "true";
        } else {
          r.error(e, "'" + t + "' is not allowed; allowed: true or false");
          ok = false;
        }
      }
    }
  }
  if (!ok) return;
  for (int a = 0; a < d; ++a) {
    const auto ua = static_cast<std::size_t>(a);
    s.box.lo[ua] = (*lo)[ua];
    s.box.hi[ua] = (*hi)[ua];
    if (!(s.box.hi[ua] > s.box.lo[ua])) {
      r.error(YamlReader::child(box, "upper"),
              "axis " + std::to_string(a) + ": upper " + format_number(s.box.hi[ua]) +
                  " must be greater than lower " + format_number(s.box.lo[ua]));
      ok = false;
    }
  }
  for (int a = d; a < 3; ++a) {
    s.box.lo[static_cast<std::size_t>(a)] = 0.0;
    s.box.hi[static_cast<std::size_t>(a)] = 0.0;
  }
  ctx.geometry_ok = ok;
}

/// Lattice neighbours of a particle inside the kernel support h (0 < |k| dx < h).
std::size_t lattice_neighbours(int d, double h_over_dx) {
  const int m = static_cast<int>(std::min(h_over_dx, 20.0));
  std::size_t n = 0;
  for (int i = -m; i <= m; ++i) {
    for (int j = d > 1 ? -m : 0; j <= (d > 1 ? m : 0); ++j) {
      for (int k = d > 2 ? -m : 0; k <= (d > 2 ? m : 0); ++k) {
        const double r2 = double(i) * i + double(j) * j + double(k) * k;
        if (r2 > 0 && r2 < h_over_dx * h_over_dx) ++n;
      }
    }
  }
  return n;
}

/// A lattice whose kernel support reaches no neighbour: nothing would diffuse
/// and the SPH sums would see only the particle itself.
void check_neighbours(SceneContext& ctx, const Field& root) {
  const Scene& s = ctx.scene;
  if (!ctx.particles_ok || !(s.lattice_spacing > 0) || !(s.fluid.smoothing_length > 0)) return;
  const bool diffuses = std::any_of(s.species.begin(), s.species.end(),
                                    [](const Species& sp) { return sp.diffusivity > 0; });
  const auto* backend = sadr::fluid::schema::find(s.fluid.backend);
  if (backend && !backend->capabilities.moves_particles && !diffuses) return;
  const double ratio = s.fluid.smoothing_length / s.lattice_spacing;
  if (lattice_neighbours(s.box.dimension, ratio * (1.0 - 1e-9)) > 0) return;
  const Field fluid = YamlReader::child(root, "fluid");
  const Field hf = YamlReader::present(YamlReader::child(fluid, "h_over_dx"))
                       ? YamlReader::child(fluid, "h_over_dx")
                       : YamlReader::child(fluid, "smoothing_length");
  ctx.reader.error(hf, "h = " + format_number(s.fluid.smoothing_length) + " is " +
                           format_number(ratio) +
                           " lattice spacings: particle 0 (and every other) "
                           "has 0 neighbours within the kernel support, so nothing diffuses and "
                           "the fluid sees no pressure; allowed: h_over_dx > 1 (typically 2-4)");
}

void read_ssa(SceneContext& ctx, const Field& root) {
  YamlReader& r = ctx.reader;
  const Field ssa = YamlReader::child(root, "ssa");
  if (!YamlReader::present(ssa)) return;
  static constexpr std::array<std::string_view, 4> kKeys{"convention", "regularization", "method",
                                                         "tolerance"};
  if (!r.expect_map(ssa, kKeys)) return;
  static constexpr std::array<std::string_view, 2> kConventions{"symmetric", "volume"};
  if (auto c = r.choice(ssa, "convention", kConventions, false, "jump convention")) {
    ctx.scene.ssa.convention =
        *c == "volume" ? JumpConvention::kVolume : JumpConvention::kSymmetric;
  }
  ctx.scene.ssa.regularization =
      r.number_or(ssa, "regularization", 0.01, Bound::kNonNegative, "dimensionless");
  static constexpr std::array<std::string_view, 2> kMethods{"exact", "adaptive"};
  if (auto m = r.choice(ssa, "method", kMethods, false, "SSA method")) {
    ctx.scene.ssa.method =
        *m == "adaptive" ? model::SsaMethod::kAdaptive : model::SsaMethod::kExact;
  }
  const Field tolerance = YamlReader::child(ssa, "tolerance");
  if (!YamlReader::present(tolerance)) return;
  if (ctx.scene.ssa.method != model::SsaMethod::kAdaptive) {
    r.error(tolerance,
            "is given with method: exact; allowed only with method: adaptive (the "
            "exact method has no tolerance)");
  } else if (auto eps = r.number(ssa, "tolerance", Bound::kPositive, "dimensionless", true)) {
    if (*eps < 1) {
      ctx.scene.ssa.tolerance = *eps;
    } else {
      r.error(tolerance,
              format_number(*eps) + " is out of range; allowed: 0 < tolerance < 1 [dimensionless]");
    }
  }
}

}  // namespace
}  // namespace detail

Scene parse_scene(std::string_view text, const std::filesystem::path& source_name,
                  std::span<const SceneOverride> overrides) {
  using namespace detail;
  Diagnostics diag(source_name.string());
  Scene scene;
  scene.source_path = source_name;
  scene.source_hash = content_hash(text);
  YAML::Node doc;
  try {
    doc = YAML::Load(std::string(text));
  } catch (const YAML::Exception& e) {
    diag.error({e.mark.line + 1, e.mark.column + 1}, "", "YAML syntax error: " + e.msg);
    diag.throw_if_any();
  }
  // The effective scene: the file's bytes, then each override as written.
  std::string effective(text);
  for (const auto& o : overrides) {
    effective += "\n--set " + o.text();
    scene.overrides.push_back(o.text());
  }
  if (!overrides.empty()) {
    scene.source_hash = content_hash(effective);
    apply_overrides(doc, overrides, diag);
    diag.throw_if_any();
  }
  YamlReader reader(diag);
  Field root{doc, "", {1, 1}};
  if (!reader.expect_map(root, kTopKeys)) diag.throw_if_any();

  SceneContext ctx{reader, scene};
  ctx.base_dir = source_name.parent_path();
  if (auto name = reader.string(root, "name", false)) {
    scene.name = *name;
    if (const auto why = invalid_scene_name(scene.name)) {
      reader.error(YamlReader::child(root, "name"), *why);
    }
  } else {
    scene.name = scene_name_from_file(source_name);
  }
  scene.description = reader.string(root, "description", false).value_or("");
  read_box(ctx, root);
  read_fluid(ctx, root);
  read_regions(ctx, root);
  if (YamlReader::present(YamlReader::child(root, "geometry"))) {
    read_geometry(ctx, root);
  } else {
    read_particles(ctx, root);
  }
  check_open_boundary(ctx);
  check_wall_planes(ctx, root);
  check_body_forces(ctx, root);
  {
    const Field fl = YamlReader::child(root, "fluid");
    choose_flow_settings(ctx, root, YamlReader::present(YamlReader::child(fl, "sound_speed")),
                         YamlReader::present(YamlReader::child(fl, "reference_density")));
  }
  read_parameters(ctx, root);
  read_species(ctx, root);
  check_parameter_names(ctx, root);
  read_reactions(ctx, root);
  read_boundary_fluxes(ctx, root);
  read_time_and_output(ctx, root);
  read_ssa(ctx, root);
  check_neighbours(ctx, root);
  scene.seed = reader.integer(root, "seed", 0, UINT64_MAX, false).value_or(0);
  if (diag.empty()) {  // silent zeros: only in a scene whose every part was read
    warn_species_never_present(ctx, root);
    warn_empty_observables(ctx, root);
  }
  if (!ctx.particle_file_bytes.empty()) {
    // A changed particle file is a changed scene (checkpoints refuse it).
    scene.source_hash = content_hash(effective + ctx.particle_file_bytes);
  }
  diag.throw_if_any();
  scene.warnings = diag.warnings();
  return scene;
}

Scene load_scene(const std::filesystem::path& path, std::span<const SceneOverride> overrides) {
  const std::string bytes = read_file_bytes(path, kMaxSceneFileBytes, "scene file");
  return parse_scene(bytes, path, overrides);
}

// ---- small Scene members -------------------------------------------------

std::string_view to_string(Splitting splitting) {
  return splitting == Splitting::kStrang ? "strang" : "lie";
}

std::string_view to_string(OutputFormat format) {
  switch (format) {
    case OutputFormat::kVtu:
      return "vtu";
    case OutputFormat::kVtp:
      return "vtp";
    case OutputFormat::kCsv:
      return "csv";
  }
  return "unknown";
}

const Species* Scene::find_species(std::string_view n) const {
  for (const auto& sp : species) {
    if (sp.name == n) return &sp;
  }
  return nullptr;
}

const AssignedSpecies* Scene::find_assigned(std::string_view n) const {
  for (const auto& a : assigned) {
    if (a.name == n) return &a;
  }
  return nullptr;
}

const Region* Scene::find_region(std::string_view n) const {
  for (const auto& rg : regions) {
    if (rg.name == n) return &rg;
  }
  return nullptr;
}

std::size_t Scene::stochastic_species_count() const {
  return static_cast<std::size_t>(
      std::count_if(species.begin(), species.end(), [](const Species& s) { return s.stochastic; }));
}

std::size_t Scene::deterministic_species_count() const {
  return species.size() - stochastic_species_count();
}

}  // namespace sadr::orchestrator
