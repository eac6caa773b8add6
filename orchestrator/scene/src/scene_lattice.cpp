// SPDX-License-Identifier: MIT
// Scene section "particles": a lattice filled region by region, or an
// explicit particle set from a CSV file; then region membership.
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "sadr/common/input_file.hpp"
#include "sadr/common/status.hpp"
#include "sadr/orchestrator/machine_limits.hpp"
#include "scene_parts.hpp"
#include "scene_wall_motion.hpp"

namespace sadr::orchestrator::detail {

namespace {

constexpr std::array<std::string_view, 4> kParticleKeys{"spacing", "density", "fill", "file"};
constexpr std::array<std::string_view, 5> kFillKeys{"region", "kind", "density", "mass_factor",
                                                    "velocity"};
constexpr std::array<std::string_view, 4> kLatticeKinds{"fluid", "wall", "inlet", "outlet"};
constexpr double kMaxLatticePoints = 5e7;

struct FillRule {
  const Region* region = nullptr;
  ParticleKind kind = ParticleKind::kFluid;
  double density = 1.0;
  double mass_factor = 1.0;
  std::array<double, 3> velocity{};
  Field velocity_field{};  ///< where a wall rule's velocity is given (moving walls)
};

/// Lattice coordinates along one axis: periodic axes get cell centres
/// lo + (k + 1/2) dx (no duplicate point at lo and hi); walled axes get
/// lo + k dx for every point up to hi (both walls included when L/dx is whole).
std::vector<double> axis_points(SceneContext& ctx, const Field& where, int axis, double dx) {
  const Box& b = ctx.scene.box;
  const auto ua = static_cast<std::size_t>(axis);
  const double length = b.length(axis);
  const double cells = length / dx;
  std::vector<double> x;
  if (cells > kMaxLatticePoints) return x;
  if (b.periodic[ua]) {
    const double n = std::round(cells);
    if (n < 1.0 || std::abs(n - cells) > 1e-6) {
      ctx.reader.error(where, format_number(dx) + " does not divide the periodic box length " +
                                  format_number(length) + " along " + "xyz"[axis] +
                                  "; allowed: a spacing with length/spacing a whole number");
      return x;
    }
    for (int k = 0; k < static_cast<int>(n); ++k) x.push_back(b.lo[ua] + (k + 0.5) * dx);
  } else {
    const int n = static_cast<int>(std::floor(cells + 1e-9)) + 1;
    for (int k = 0; k < n; ++k) x.push_back(std::min(b.lo[ua] + k * dx, b.hi[ua]));
  }
  return x;
}

/// A lattice whose particles alone (sadr and fluid_service, before any
/// species) need more memory than the machine has is refused before it is built.
std::optional<std::string> lattice_memory_refusal(const SceneContext& ctx, double points) {
  const int d = ctx.scene.box.dimension;
  const double need = orchestrator_memory(ctx.scene.fluid.backend).at(points) +
                      (moves_particles(ctx.scene.fluid.backend)
                           ? fluid_memory(ctx.scene.fluid.backend, d).at(points)
                           : 0.0);
  const MachineLimits m = machine_limits(".");
  if (need <= m.memory_bytes) return std::nullopt;
  return format_number(points) + " lattice points need at least " + format_number(need / 1e9) +
         " GB (sadr and fluid_service, measured bytes per particle), more than the " +
         m.memory_source + " of " + format_number(m.memory_bytes / 1e9) +
         " GB; allowed: a coarser spacing";
}

void build_lattice(SceneContext& ctx, const Field& particles, double dx, double density) {
  YamlReader& r = ctx.reader;
  Scene& s = ctx.scene;
  const int d = s.box.dimension;
  std::vector<FillRule> rules;
  const Field fill = YamlReader::child(particles, "fill");
  if (!YamlReader::present(fill)) {
    rules.push_back(FillRule{&ctx.all_region, ParticleKind::kFluid, density, 1.0, {}});
  } else if (r.expect_sequence(fill)) {
    for (std::size_t i = 0; i < fill.node.size(); ++i) {
      const Field f = YamlReader::element(fill, i);
      if (!r.expect_map(f, kFillKeys)) continue;
      FillRule rule;
      const std::string name = r.string(f, "region", false).value_or(std::string(kAllRegion));
      rule.region = lookup_region(ctx, YamlReader::child(f, "region"), name);
      if (rule.region && !rule.region->kinds.empty()) {
        r.error(YamlReader::child(f, "region"),
                "region '" + name +
                    "' has a kinds filter, which has no meaning before particles exist; use a "
                    "region without 'kinds' to fill the lattice");
      } else if (rule.region && rule.region->shape == RegionShape::kIds) {
        r.error(YamlReader::child(f, "region"),
                "region '" + name +
                    "' lists particle ids, which do not exist before the lattice is filled; "
                    "use a region with a shape");
      }
      if (auto k = r.choice(f, "kind", kLatticeKinds, false, "particle kind")) {
        rule.kind = *parse_kind(*k);
      }
      rule.density = r.number_or(f, "density", density, Bound::kPositive, "mass/length^d");
      rule.mass_factor = r.number_or(f, "mass_factor", 1.0, Bound::kPositive, "dimensionless");
      if (ctx.dimension_ok) {
        if (auto v = r.vector(f, "velocity", d, "length/time", false)) rule.velocity = *v;
      }
      // A wall rule's velocity is the walls' prescribed velocity (they keep their positions).
      rule.velocity_field = YamlReader::child(f, "velocity");
      if (rule.kind == ParticleKind::kWall &&
          std::any_of(rule.velocity.begin(), rule.velocity.end(),
                      [](double v) { return v != 0; })) {
        require_moving_walls(ctx, rule.velocity_field);
      }
      if (rule.region) rules.push_back(rule);
    }
  }
  if (!ctx.geometry_ok) return;
  // Count the points before making any: a spacing far too fine is refused
  // with the count (and its memory), not with "no point in any region" or a
  // failed allocation.
  double points = 1.0;
  for (int a = 0; a < d; ++a) points *= std::floor(s.box.length(a) / dx + 1e-9) + 1.0;
  if (points > kMaxLatticePoints) {
    r.error(YamlReader::child(particles, "spacing"),
            format_number(dx) + " gives " + format_number(points) +
                " lattice points; allowed: at most 5e7 (a coarser spacing)");
    return;
  }
  if (const auto why = lattice_memory_refusal(ctx, points)) {
    r.error(YamlReader::child(particles, "spacing"), *why);
    return;
  }
  std::array<std::vector<double>, 3> axes{std::vector<double>{0.0}, std::vector<double>{0.0},
                                          std::vector<double>{0.0}};
  double total = 1.0;
  for (int a = 0; a < d; ++a) {
    axes[static_cast<std::size_t>(a)] =
        axis_points(ctx, YamlReader::child(particles, "spacing"), a, dx);
    total *= static_cast<double>(axes[static_cast<std::size_t>(a)].size());
  }
  if (total > kMaxLatticePoints || total == 0.0) {
    if (total > kMaxLatticePoints) {
      r.error(
          YamlReader::child(particles, "spacing"),
          format_number(dx) + " gives more than 5e7 lattice points; allowed: a coarser spacing");
    }
    return;
  }
  const double cell_volume = std::pow(dx, d);
  const double tol = ctx.tolerance();
  ParticleState& p = s.particles;
  p.dimension = d;
  std::vector<std::vector<std::uint32_t>> members(rules.size());  // moving wall rules' particles
  for (const double z : axes[2]) {
    for (const double y : axes[1]) {
      for (const double x : axes[0]) {
        const std::array<double, 3> pos{x, y, z};
        for (const auto& rule : rules) {
          if (!rule.region->contains(pos, d, tol)) continue;
          p.positions.insert(p.positions.end(), pos.begin(), pos.end());
          p.velocities.insert(p.velocities.end(), rule.velocity.begin(), rule.velocity.end());
          p.densities.push_back(rule.density);
          p.masses.push_back(rule.density * cell_volume * rule.mass_factor);
          p.kinds.push_back(rule.kind);
          const auto k = static_cast<std::size_t>(&rule - rules.data());
          if (rule.kind == ParticleKind::kWall) {
            members[k].push_back(static_cast<std::uint32_t>(p.kinds.size() - 1));
          }
          break;
        }
      }
    }
  }
  for (std::size_t k = 0; k < rules.size(); ++k) {
    check_face_wall_motion(ctx, rules[k].velocity_field, rules[k].velocity, members[k]);
  }
}

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> out(1);
  for (const char c : line) {
    if (c == ',') {
      out.emplace_back();
    } else if (c != '\r' && c != ' ' && c != '\t') {
      out.back() += c;
    }
  }
  return out;
}

void read_particle_file(SceneContext& ctx, const Field& file_field, const std::string& name) {
  YamlReader& r = ctx.reader;
  Scene& s = ctx.scene;
  const std::filesystem::path path =
      std::filesystem::path(name).is_absolute() ? std::filesystem::path(name) : ctx.base_dir / name;
  try {
    require_regular_file(path, kMaxDataFileBytes, "particle file");
  } catch (const InvalidArgument& e) {
    r.error(file_field,
            std::string(e.what()) + " (paths are relative to the scene file's directory)");
    return;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    r.error(file_field, "cannot open particle file '" + path.string() +
                            "' (paths are relative to the scene file's directory)");
    return;
  }
  static constexpr std::array<std::string_view, 9> kColumns{"x",    "y",  "z",  "mass", "density",
                                                            "kind", "vx", "vy", "vz"};
  {
    std::ostringstream bytes;
    bytes << in.rdbuf();
    ctx.particle_file_bytes = bytes.str();
  }
  std::istringstream rows(ctx.particle_file_bytes);
  std::string line;
  const std::string where0 = path.string() + ":1: ";
  if (!std::getline(rows, line) || line.find_first_not_of(" \t\r") == std::string::npos) {
    r.error(file_field, where0 +
                            "empty header row; the first line must name the columns x, y, "
                            "z, mass, density, kind (and optionally vx, vy, vz)");
    return;
  }
  const auto header = split_csv_line(line);
  std::map<std::string, std::size_t> col;
  std::vector<std::pair<std::size_t, std::size_t>> extra;  // (csv column, extra_columns index)
  for (std::size_t c = 0; c < header.size(); ++c) {
    if (col.count(header[c])) {
      r.error(file_field, where0 + "column '" + header[c] + "' appears twice (columns " +
                              std::to_string(col[header[c]] + 1) + " and " + std::to_string(c + 1) +
                              "); each column must be named once");
    } else if (std::find(kColumns.begin(), kColumns.end(), header[c]) != kColumns.end()) {
      col[header[c]] = c;
    } else if (valid_identifier(header[c])) {
      // a species value column, checked against the species' initial entries later
      col[header[c]] = c;
      extra.emplace_back(c, ctx.extra_columns.size());
      ctx.extra_columns.push_back({header[c], {}, false});
    } else {
      r.error(file_field, where0 + "column '" + header[c] +
                              "' is not a column name (allowed: x, y, z, mass, density, kind, vx, "
                              "vy, vz, or a name [A-Za-z_][A-Za-z0-9_]* read by a species' "
                              "count_column or concentration_column)");
    }
  }
  ctx.particle_file = path.string();
  ctx.particle_file_field = file_field;
  bool columns_ok = true;
  for (const std::string_view need : {"x", "y", "z", "mass", "density", "kind"}) {
    if (!col.count(std::string(need))) {
      columns_ok = false;
      r.error(file_field, where0 + "missing column '" + std::string(need) +
                              "'; the header row must name x, y, z, mass, density, kind");
    }
  }
  if (!columns_ok) return;
  ParticleState& p = s.particles;
  p.dimension = s.box.dimension;
  const double tol = ctx.tolerance();
  int line_no = 1;
  std::size_t reported = 0;
  auto report = [&](const std::string& msg) {
    if (++reported <= 20)
      r.error(file_field, path.string() + ":" + std::to_string(line_no) + ": " + msg);
  };
  while (std::getline(rows, line)) {
    ++line_no;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const auto cells = split_csv_line(line);
    if (cells.size() != header.size()) {
      report("expected " + std::to_string(header.size()) + " values, got " +
             std::to_string(cells.size()));
      continue;
    }
    auto number = [&](const char* column, double fallback) {
      auto it = col.find(column);
      if (it == col.end()) return fallback;
      const std::string& t = cells[it->second];
      double v = 0.0;
      auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
      if (ec != std::errc() || ptr != t.data() + t.size() || !std::isfinite(v)) {
        report(std::string("column '") + column + "': '" + t + "' is not a finite number");
        return std::nan("");
      }
      return v;
    };
    const std::array<double, 3> x{number("x", 0), number("y", 0), number("z", 0)};
    const double m = number("mass", 1);
    const double rho = number("density", 1);
    const std::array<double, 3> v{number("vx", 0), number("vy", 0), number("vz", 0)};
    const std::string& kind_text = cells[col["kind"]];
    std::optional<ParticleKind> kind = parse_kind(kind_text);
    if (!kind && kind_text.size() == 1 && kind_text[0] >= '0' && kind_text[0] <= '3') {
      kind = static_cast<ParticleKind>(kind_text[0] - '0');
    }
    if (!kind)
      report("column 'kind': unknown particle kind '" + kind_text +
             "' (allowed: fluid, wall, inlet, outlet or 0-3)");
    if (!(m > 0.0)) report("column 'mass': " + format_number(m) + " is out of range; allowed: > 0");
    if (!(rho > 0.0)) {
      report("column 'density': " + format_number(rho) + " is out of range; allowed: > 0");
    }
    for (int a = 0; a < 3; ++a) {
      const auto ua = static_cast<std::size_t>(a);
      const bool active = a < s.box.dimension;
      if (active && ctx.geometry_ok && (x[ua] < s.box.lo[ua] - tol || x[ua] > s.box.hi[ua] + tol)) {
        report(std::string("particle at ") + "xyz"[a] + " = " + format_number(x[ua]) +
               " is outside the box [" + format_number(s.box.lo[ua]) + ", " +
               format_number(s.box.hi[ua]) + "]");
      }
      if (!active && x[ua] != 0.0) {
        report(std::string("column '") + "xyz"[a] + "' must be 0 in a " +
               std::to_string(s.box.dimension) + "D scene, got " + format_number(x[ua]));
      }
    }
    if (kind == ParticleKind::kWall && (v[0] != 0 || v[1] != 0 || v[2] != 0) &&
        !backend_moves_walls(ctx)) {
      report("a wall particle with a velocity (a moving wall): the fluid backend '" +
             s.fluid.backend + "' keeps walls at rest; allowed with: sdpd");
    }
    p.positions.insert(p.positions.end(), x.begin(), x.end());
    p.velocities.insert(p.velocities.end(), v.begin(), v.end());
    p.masses.push_back(m);
    p.densities.push_back(rho);
    p.kinds.push_back(kind.value_or(ParticleKind::kFluid));
    for (const auto& [c, e] : extra) {
      ctx.extra_columns[e].values.push_back(number(header[c].c_str(), 0));
    }
    ctx.particle_lines.push_back(line_no);
  }
  if (p.kinds.empty() && reported == 0) {
    r.error(file_field, path.string() + ":" + std::to_string(line_no + 1) +
                            ": no particle rows after the header; the file must list at least "
                            "one particle");
  }
  if (reported > 20) {
    r.error(file_field, path.string() + ": " + std::to_string(reported - 20) + " more problems");
  }
}

}  // namespace

void read_particles(SceneContext& ctx, const Field& root) {
  YamlReader& r = ctx.reader;
  Scene& s = ctx.scene;
  const Field particles = YamlReader::child(root, "particles");
  if (!YamlReader::present(particles)) {
    r.error(particles,
            "missing; required: a map with 'spacing' (lattice) or 'file' (CSV), or instead a "
            "top-level 'geometry' section (particles from shapes and meshes)");
    return;
  }
  if (!r.expect_map(particles, kParticleKeys)) return;
  const std::size_t errors_before = r.diag().size();
  const double density = r.number_or(particles, "density", s.fluid.reference_density,
                                     Bound::kPositive, "mass/length^d");
  const Field file = YamlReader::child(particles, "file");
  const Field spacing = YamlReader::child(particles, "spacing");
  if (YamlReader::present(file)) {
    if (YamlReader::present(YamlReader::child(particles, "fill"))) {
      r.error(YamlReader::child(particles, "fill"),
              "'fill' applies to lattices only; a particle file gives every particle's kind");
    }
    if (YamlReader::present(spacing)) {
      s.lattice_spacing =
          r.number(particles, "spacing", Bound::kPositive, "length", false).value_or(0.0);
    }
    if (auto name = r.string(particles, "file", true)) read_particle_file(ctx, file, *name);
  } else {
    const auto dx = r.number(particles, "spacing", Bound::kPositive, "length", true);
    if (dx) {
      s.lattice_spacing = *dx;
      build_lattice(ctx, particles, *dx, density);
    }
  }
  if (ctx.h_over_dx) {
    if (s.lattice_spacing > 0.0) {
      s.fluid.smoothing_length = *ctx.h_over_dx * s.lattice_spacing;
    } else {
      r.error(YamlReader::child(YamlReader::child(root, "fluid"), "h_over_dx"),
              "needs particles.spacing (the particle file gives no lattice spacing); give "
              "fluid.smoothing_length or particles.spacing");
    }
  }
  if (!ctx.geometry_ok || r.diag().size() != errors_before) return;
  const std::size_t n = s.particles.densities.size();
  if (n == 0) {
    r.error(particles, "no particles: no lattice point lies in any 'fill' region");
    return;
  }
  s.particles.ids.resize(n);
  for (std::size_t i = 0; i < n; ++i) s.particles.ids[i] = i;
  resolve_regions(ctx, s.particles);
  ctx.particles_ok = true;
}

void resolve_regions(SceneContext& ctx, const ParticleState& particles) {
  const std::size_t n = particles.size();
  for (const auto& [index, field] : ctx.id_regions) {
    const Region& rg = ctx.scene.regions[index];
    if (!rg.ids.empty() && rg.ids.back() >= n) {
      ctx.reader.error(field, "particle id " + std::to_string(rg.ids.back()) + " of region '" +
                                  rg.name + "' does not exist; allowed: ids 0 to " +
                                  std::to_string(n - 1) + " (" + std::to_string(n) + " particles)");
    }
  }
  const double tol = ctx.tolerance();
  resolve_membership(ctx.all_region, particles, tol);
  for (auto& rg : ctx.scene.regions) resolve_membership(rg, particles, tol);
}

}  // namespace sadr::orchestrator::detail
