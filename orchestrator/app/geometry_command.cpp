// SPDX-License-Identifier: MIT
// `sadr geometry SCENE -o DIR`: the particles a scene's `geometry` section makes, as CSV and VTU
// (kind, surface id and distance, volume, density error, one 0/1 column per region), and a
// summary: counts per kind, fluid volume against the exact one, density error, smallest feature.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "cli.hpp"
#include "commands.hpp"
#include "sadr/common/log.hpp"
#include "sadr/common/status.hpp"
#include "sadr/orchestrator/frame_writers.hpp"
#include "sadr/orchestrator/scene_geometry.hpp"
#include "sadr/orchestrator/scene_loader.hpp"
#include "sadr/orchestrator/scene_override.hpp"

namespace sadr::orchestrator {
namespace {

struct GeometryCommandOptions {
  std::string scene;
  std::vector<std::string> overrides;  ///< --set PATH=VALUE
  std::string output;                  ///< -o DIR ("" = ./geometry)
};

std::string num(double v, int digits = 6) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

int cmd_geometry(const GeometryCommandOptions& o) {
  namespace fs = std::filesystem;
  Scene scene;
  try {
    scene = load_scene(o.scene, parse_overrides(o.overrides));
  } catch (const InvalidArgument& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return kExitInvalidInput;
  }
  for (const auto& w : scene.warnings) log::warn(w);
  if (!scene.geometry) {
    std::fprintf(stderr,
                 "%s: the scene has no 'geometry' section (its particles come from 'particles'); "
                 "sadr geometry shows the particles that section makes\n",
                 o.scene.c_str());
    return kExitInvalidInput;
  }
  const GeometryReport& g = *scene.geometry;
  const ParticleState& p = scene.particles;
  const std::size_t n = p.size();
  const int d = scene.box.dimension;
  const GeometryDensityError err = geometry_density_error(scene);

  std::vector<SpeciesColumn> cols;
  cols.push_back({"surface_id", {}});
  cols.push_back({"surface_distance", {}});
  cols.push_back({"volume", {}});
  cols.push_back({"density_error", err.per_particle});
  for (std::size_t i = 0; i < n; ++i) {
    cols[0].values.push_back(static_cast<double>(g.surface_id[i]));
    cols[1].values.push_back(std::isfinite(g.surface_distance[i]) ? g.surface_distance[i] : -1.0);
    cols[2].values.push_back(p.volume(i));
  }
  for (const auto& rg : scene.regions) {
    SpeciesColumn c{"region_" + rg.name, std::vector<double>(n, 0.0)};
    for (const auto k : rg.particles) c.values[k] = 1.0;
    cols.push_back(std::move(c));
  }
  const fs::path dir = o.output.empty() ? fs::path("geometry") : fs::path(o.output);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw IoError("cannot create '" + dir.string() + "': " + ec.message());
  write_frame_csv(dir / "particles.csv", 0.0, p, cols);
  write_vtu(dir / "particles.vtu", 0.0, p, cols, scene.output.vtk_encoding);

  std::size_t per_kind[4] = {0, 0, 0, 0};
  for (std::size_t i = 0; i < n; ++i) ++per_kind[static_cast<int>(p.kind(i))];
  const double dx = g.spacing, h = scene.fluid.smoothing_length;
  std::printf(
      "%s: %dD, %s lattice, spacing %s, kernel support h = %s (%s spacings), walls %s "
      "deep\n",
      o.scene.c_str(), d, g.lattice.c_str(), num(dx).c_str(), num(h).c_str(),
      num(h / dx, 4).c_str(), num(g.wall_depth).c_str());
  std::printf("  particles: %zu (fluid %zu, wall %zu)\n", n, per_kind[0], per_kind[1]);
  std::printf("  bodies:\n");
  for (const auto& b : g.bodies) {
    std::printf("    %-16s %-6s", b.name.c_str(), b.role.c_str());
    if (b.surface_id >= 0) std::printf("  surface id %d", b.surface_id);
    if (b.exact_volume)
      std::printf("  shape %s %s", d == 2 ? "area" : "volume", num(*b.exact_volume).c_str());
    std::printf("  (%s)\n", b.origin.c_str());
  }
  const char* vol = d == 2 ? "area" : "volume";
  std::printf("  fluid %s: %s (N dx^%d = %s)", vol, num(g.fluid_volume, 8).c_str(), d,
              num(g.lattice_fluid_volume, 8).c_str());
  if (g.exact_fluid_volume) {
    std::printf("; exact %s, lattice error %s %%\n", num(*g.exact_fluid_volume, 8).c_str(),
                num(100.0 * (g.lattice_fluid_volume / *g.exact_fluid_volume - 1.0), 3).c_str());
  } else {
    std::printf("; no exact %s known for these shapes\n", vol);
  }
  std::printf("  density error |n_i / n_ref - 1| over the fluid: max %s, RMS %s\n",
              num(err.max, 3).c_str(), num(err.rms, 3).c_str());
  if (g.relaxed) {
    std::printf("  relaxation: %d iterations; before max %s, RMS %s\n", g.relax_iterations,
                num(g.max_error_before, 3).c_str(), num(g.rms_error_before, 3).c_str());
  }
  if (std::isfinite(g.smallest_feature)) {
    std::printf("  smallest feature: %s spacings (%s)%s\n", num(g.smallest_feature / dx, 3).c_str(),
                g.smallest_feature_where.c_str(),
                g.smallest_feature < h ? ": THINNER THAN THE KERNEL SUPPORT" : "");
  } else {
    std::printf("  smallest feature: none thinner than %s spacings (the search's reach)\n",
                num(g.feature_search / dx, 3).c_str());
  }
  std::printf("  regions:");
  for (const auto& rg : scene.regions) {
    std::printf(" %s %zu", rg.name.c_str(), rg.particles.size());
    if (&rg != &scene.regions.back()) std::printf(",");
  }
  std::printf("\n");
  for (const auto& note : g.notes) std::printf("  note: %s\n", note.c_str());
  std::printf("  warnings: %zu\n", scene.warnings.size());
  std::printf("wrote %s and %s\n", (dir / "particles.csv").string().c_str(),
              (dir / "particles.vtu").string().c_str());
  return kExitOk;
}

}  // namespace

Subcommand add_geometry_command(CLI::App& app) {
  auto o = std::make_shared<GeometryCommandOptions>();
  auto* geometry = app.add_subcommand(
      "geometry",
      "write the particles a scene's `geometry` section makes (DIR/particles.csv and .vtu: kind, "
      "surface, volume, density error, regions) and print counts, volumes, density error and "
      "the smallest feature");
  geometry->add_option("scene", o->scene, "scene file (YAML)")
      ->required()
      ->check(CLI::ExistingFile);
  geometry->add_option("-o,--output", o->output, "output directory (default: ./geometry)");
  add_set_option(geometry, o->overrides);
  return {geometry, [o] { return cmd_geometry(*o); }};
}

}  // namespace sadr::orchestrator
