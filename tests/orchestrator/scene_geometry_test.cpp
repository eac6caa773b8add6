// SPDX-License-Identifier: MIT
// The scene section `geometry` (scene_geometry.cpp): particles from bodies (shapes, CSG, STL),
// regions and surface layers, masses from volumes, and refusals with file:line.
#include <gtest/gtest.h>

#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "sadr/common/status.hpp"
#include "sadr/orchestrator/hash.hpp"
#include "sadr/orchestrator/scene_geometry.hpp"
#include "sadr/orchestrator/scene_loader.hpp"
#include "scene_test_support.hpp"

namespace sadr::orchestrator {
namespace {

using test::replace_once;

/// A 2D periodic channel (walls below y = 0 and above y = 1) with an elliptic cell; the number
/// after each line is its line.
const std::string kChannel =
    "dimension: 2\n"                                                             // 1
    "box: {lower: [0.0, -0.15], upper: [2.0, 1.15], periodic: [true, false]}\n"  // 2
    "geometry:\n"                                                                // 3
    "  spacing: 0.05\n"                                                          // 4
    "  bodies:\n"                                                                // 5
    "    - name: channel\n"                                                      // 6
    "      role: fluid\n"                                                        // 7
    "      shape: {type: box, lower: [-1.0, 0.0], upper: [3.0, 1.0]}\n"          // 8
    "    - name: cell\n"                                                         // 9
    "      role: solid\n"                                                        // 10
    "      shape: {type: ellipse, center: [0.7, 0.5], radii: [0.2, 0.15]}\n"     // 11
    "      wall_layer: membrane\n"                                               // 12
    "      fluid_layer: near_cell\n"                                             // 13
    "fluid: {backend: static, h_over_dx: 3.0, reference_density: 2.0}\n"         // 14
    "species:\n"                                                                 // 15
    "  - name: R\n"                                                              // 16
    "    diffusivity: 0.0\n"                                                     // 17
    "    initial: [{region: membrane, count: 5}]\n"                              // 18
    "    boundaries: [{region: membrane, condition: free}]\n"                    // 19
    "time: {coupling_step: 0.1, end: 0.2}\n";                                    // 20

std::string error_of(const std::string& text, const std::filesystem::path& file = "scene.yaml") {
  try {
    (void)parse_scene(text, file);
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "<no error>";
}

double fluid_mass(const Scene& s) {
  double m = 0;
  for (std::size_t i = 0; i < s.particles.size(); ++i) {
    if (s.particles.kind(i) == ParticleKind::kFluid) m += s.particles.masses[i];
  }
  return m;
}

TEST(SceneGeometry, ChannelWithCellMakesParticlesRegionsAndMasses) {
  const Scene s = parse_scene(kChannel, "scene.yaml");
  ASSERT_TRUE(s.geometry);
  EXPECT_DOUBLE_EQ(s.lattice_spacing, 0.05);
  EXPECT_NEAR(s.fluid.smoothing_length, 0.15, 1e-15);
  const std::size_t n = s.particles.size();
  ASSERT_GT(n, 0U);
  // 40 columns x 26 rows of sites: the cell is 2 h thick, so all of it is wall.
  EXPECT_EQ(n, 40U * 26U);
  std::size_t walls = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = s.particles.positions[3 * i], y = s.particles.positions[3 * i + 1];
    EXPECT_GE(x, 0.0);
    EXPECT_LT(x, 2.0);
    EXPECT_GE(y, -0.15);
    EXPECT_LT(y, 1.15);
    const bool in_cell = std::pow((x - 0.7) / 0.2, 2) + std::pow((y - 0.5) / 0.15, 2) < 1;
    const bool fluid_expected = y > 0 && y < 1 && !in_cell;
    EXPECT_EQ(s.particles.kind(i) == ParticleKind::kFluid, fluid_expected) << x << " " << y;
    walls += s.particles.kind(i) == ParticleKind::kWall;
  }
  // Three wall rows below and above (depth 0.025, 0.075, 0.125 <= h = 0.15).
  EXPECT_GE(walls, 6U * 40U);
  // Fluid mass = rho_0 times the exact fluid area 2 - pi 0.2 0.15.
  const double area = 2.0 - std::numbers::pi * 0.2 * 0.15;
  ASSERT_TRUE(s.geometry->exact_fluid_volume);
  EXPECT_NEAR(*s.geometry->exact_fluid_volume, area, 1e-12);
  EXPECT_NEAR(fluid_mass(s), 2.0 * area, 1e-9);
  // Regions: each body and its layers.
  const Region* channel = s.find_region("channel");
  const Region* cell = s.find_region("cell");
  const Region* membrane = s.find_region("membrane");
  const Region* near = s.find_region("near_cell");
  ASSERT_TRUE(channel && cell && membrane && near);
  const int cell_id = s.geometry->bodies[1].surface_id;
  EXPECT_EQ(s.geometry->bodies[1].role, "solid");
  for (const auto i : membrane->particles) {
    EXPECT_EQ(s.particles.kind(i), ParticleKind::kWall);
    EXPECT_EQ(s.geometry->surface_id[i], cell_id);
    EXPECT_LT(s.geometry->surface_distance[i], 0.05);
  }
  for (const auto i : near->particles) {
    EXPECT_EQ(s.particles.kind(i), ParticleKind::kFluid);
    EXPECT_EQ(s.geometry->surface_id[i], cell_id);
  }
  for (const auto i : cell->particles) EXPECT_EQ(s.particles.kind(i), ParticleKind::kWall);
  EXPECT_GT(membrane->particles.size(), 10U);
  EXPECT_GT(near->particles.size(), 10U);
  EXPECT_GT(cell->particles.size(), membrane->particles.size());
  // The perimeter of the ellipse is about 1.1: one layer of about 1.1 / dx = 22 particles.
  EXPECT_NEAR(static_cast<double>(membrane->particles.size()), 22.0, 8.0);
  // The species reads the region like any other.
  const Species* r = s.find_species("R");
  ASSERT_NE(r, nullptr);
  double total = 0;
  for (const double c : r->initial) total += c;
  EXPECT_DOUBLE_EQ(total, 5.0 * static_cast<double>(membrane->particles.size()));
  // On the lattice, the fluid's SPH density is the ideal lattice's where walls reach h.
  const GeometryDensityError e = geometry_density_error(s);
  EXPECT_LT(e.max, 1e-9);
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
}

TEST(SceneGeometry, WithoutAFluidBodyTheBoxIsFluid) {
  const std::string text =
      replace_once(replace_once(kChannel,
                                "    - name: channel\n      role: fluid\n"
                                "      shape: {type: box, lower: [-1.0, 0.0], upper: [3.0, 1.0]}\n",
                                ""),
                   "      fluid_layer: near_cell\n", "");
  const Scene s = parse_scene(text, "scene.yaml");
  std::size_t fluid = 0;
  for (std::size_t i = 0; i < s.particles.size(); ++i) {
    fluid += s.particles.kind(i) == ParticleKind::kFluid;
  }
  const double area = 2.0 * 1.3 - std::numbers::pi * 0.2 * 0.15;
  EXPECT_NEAR(static_cast<double>(fluid) * 0.05 * 0.05, area, 0.02 * area);
  EXPECT_NEAR(fluid_mass(s), 2.0 * area, 1e-9);
}

TEST(SceneGeometry, NoExactVolumeForASolidCutByTheBox) {
  // The cell crosses the periodic face x = 0, where shapes are not wrapped: the part outside
  // the box is not in the domain, so the ellipse's area is not subtracted as a whole.
  const Scene s =
      parse_scene(replace_once(kChannel, "center: [0.7, 0.5]", "center: [0.1, 0.5]"), "scene.yaml");
  EXPECT_FALSE(s.geometry->exact_fluid_volume);
  EXPECT_NEAR(fluid_mass(s), 2.0 * s.geometry->lattice_fluid_volume, 1e-9);
}

TEST(SceneGeometry, NestedCsgAndRegionBodies) {
  std::string text = replace_once(
      kChannel, "      shape: {type: ellipse, center: [0.7, 0.5], radii: [0.2, 0.15]}\n",
      "      shape:\n"
      "        type: difference\n"
      "        shapes:\n"
      "          - {type: union, shapes: [{type: disk, center: [0.5, 0.5], radius: 0.2},\n"
      "                                   {type: disk, center: [1.5, 0.5], radius: 0.2}]}\n"
      "          - {type: box, lower: [0.0, 0.0], upper: [2.0, 0.5], translate: [0.0, 0.6]}\n");
  text =
      replace_once(text, "      fluid_layer: near_cell\n",
                   "      fluid_layer: near_cell\n"
                   "    - name: middle\n"
                   "      role: region\n"
                   "      shape: {type: polygon, vertices: [[0.9, 0.1], [1.1, 0.1], [1.0, 0.9]]}\n"
                   "      kinds: [fluid]\n");
  const Scene s = parse_scene(text, "scene.yaml");
  for (std::size_t i = 0; i < s.particles.size(); ++i) {
    const double x = s.particles.positions[3 * i], y = s.particles.positions[3 * i + 1];
    const bool in_disk = std::hypot(x - 0.5, y - 0.5) < 0.2 || std::hypot(x - 1.5, y - 0.5) < 0.2;
    if (in_disk && y < 0.6) {
      EXPECT_EQ(s.particles.kind(i), ParticleKind::kWall) << x << " " << y;
    }
    if (in_disk && y > 0.6 && y < 1) {
      EXPECT_EQ(s.particles.kind(i), ParticleKind::kFluid) << x << " " << y;
    }
  }
  const Region* middle = s.find_region("middle");
  ASSERT_NE(middle, nullptr);
  EXPECT_GT(middle->particles.size(), 5U);
  for (const auto i : middle->particles) {
    EXPECT_EQ(s.particles.kind(i), ParticleKind::kFluid);
    EXPECT_NEAR(s.particles.positions[3 * i], 1.0, 0.1 + 1e-9);
  }
  // Two half disks cut by a box: no exact area is claimed.
  EXPECT_FALSE(s.geometry->exact_fluid_volume);
}

TEST(SceneGeometry, RelaxationEvensTheDensity) {
  std::string text = replace_once(kChannel, "  spacing: 0.05\n",
                                  "  spacing: 0.05\n  lattice: hexagonal\n"
                                  "  relax: {tolerance: 0.01, max_iterations: 200}\n");
  text = replace_once(text, "[true, false]", "[false, false]");
  const Scene s = parse_scene(text, "scene.yaml");
  ASSERT_TRUE(s.geometry->relaxed);
  EXPECT_EQ(s.geometry->density_error.size(), s.particles.size());
  EXPECT_LT(s.geometry->max_error, s.geometry->max_error_before);
  const GeometryDensityError e = geometry_density_error(s);
  EXPECT_NEAR(e.max, s.geometry->max_error, 1e-9);
}

std::string write_cube_stl(const std::filesystem::path& path, bool inverted) {
  // Unit cube [0.3, 0.7]^3 as 12 triangles, outward (or inward) normals.
  const double a = 0.3, b = 0.7;
  const double v[8][3] = {{a, a, a}, {b, a, a}, {b, b, a}, {a, b, a},
                          {a, a, b}, {b, a, b}, {b, b, b}, {a, b, b}};
  const int f[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                        {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  std::ofstream out(path);
  out << "solid cube\n";
  for (const auto& t : f) {
    out << " facet normal 0 0 0\n  outer loop\n";
    for (int k = 0; k < 3; ++k) {
      const int idx = inverted ? t[2 - k] : t[k];
      out << "   vertex " << v[idx][0] << " " << v[idx][1] << " " << v[idx][2] << "\n";
    }
    out << "  endloop\n endfacet\n";
  }
  out << "endsolid cube\n";
  return path.filename().string();
}

const std::string kCubeScene =
    "dimension: 3\n"
    "box: {lower: [0, 0, 0], upper: [1, 1, 1], periodic: [true, true, true]}\n"
    "geometry:\n"
    "  spacing: 0.05\n"
    "  bodies:\n"
    "    - {name: block, role: solid, shape: {type: mesh, file: MESH}, wall_layer: skin}\n"
    "fluid: {backend: static, h_over_dx: 2.0}\n"
    "time: {coupling_step: 0.1, end: 0.2}\n";

struct TempDir {
  std::filesystem::path path;
  TempDir() {
    path = std::filesystem::temp_directory_path() /
           ("sadr_geometry_test_" + std::to_string(::getpid()));
    std::filesystem::create_directories(path);
  }
  ~TempDir() { std::filesystem::remove_all(path); }
};

TEST(SceneGeometry, StlMeshAsASolidWithItsSkin) {
  TempDir dir;
  const std::string name = write_cube_stl(dir.path / "cube.stl", false);
  const std::string text = replace_once(kCubeScene, "MESH", name);
  const Scene s = parse_scene(text, dir.path / "scene.yaml");
  std::size_t fluid = 0;
  for (std::size_t i = 0; i < s.particles.size(); ++i) {
    const double* x = &s.particles.positions[3 * i];
    const bool in =
        x[0] > 0.3 && x[0] < 0.7 && x[1] > 0.3 && x[1] < 0.7 && x[2] > 0.3 && x[2] < 0.7;
    EXPECT_EQ(s.particles.kind(i) == ParticleKind::kWall, in);
    fluid += !in;
  }
  EXPECT_EQ(fluid, 8000U - 512U);  // 20^3 sites, 8^3 inside the cube
  const Region* skin = s.find_region("skin");
  ASSERT_NE(skin, nullptr);
  EXPECT_EQ(skin->particles.size(), 512U - 6U * 6U * 6U);  // the outer shell of 8^3
  // The mesh's bytes are part of the scene's hash.
  EXPECT_NE(s.source_hash, content_hash(text));
  EXPECT_TRUE(s.warnings.empty());
}

TEST(SceneGeometry, InvertedMeshIsFlippedAndSaid) {
  TempDir dir;
  const std::string name = write_cube_stl(dir.path / "inverted.stl", true);
  const Scene s = parse_scene(replace_once(kCubeScene, "MESH", name), dir.path / "scene.yaml");
  ASSERT_EQ(s.warnings.size(), 1U);
  EXPECT_NE(s.warnings[0].find("inward normals"), std::string::npos) << s.warnings[0];
  EXPECT_NE(s.warnings[0].find("scene.yaml:6:"), std::string::npos) << s.warnings[0];
  EXPECT_EQ(s.find_region("skin")->particles.size(), 512U - 216U);
}

TEST(SceneGeometry, RefusalsNameFileLineAndWhatIsAllowed) {
  struct Case {
    const char* from;
    const char* to;
    const char* expected;
  };
  const Case cases[] = {
      {"type: ellipse", "type: elipse",
       "scene.yaml:11:21: geometry.bodies[1].shape.type: unknown shape type 'elipse'; did you "
       "mean 'ellipse'?"},
      {"type: ellipse", "type: ellipsoid", "shape type 'ellipsoid' is 3D, the scene 2D"},
      {"radii: [0.2, 0.15]", "radii: [0.2, 0.15], radius: 1",
       "key 'radius' does not apply to shape type 'ellipse'"},
      {"      role: solid\n", "      role: solod\n",
       "scene.yaml:10:13: geometry.bodies[1].role: unknown role 'solod'; did you mean 'solid'?"},
      {"center: [0.7, 0.5]", "center: [7.0, 5.0]", "the shape lies outside the box"},
      {"  spacing: 0.05\n", "  spacing: 0.05\n  lattice: cubik\n", "did you mean 'cubic'?"},
      {"fluid: {backend: static,", "particles: {spacing: 0.1}\nfluid: {backend: static,",
       "'particles' and 'geometry' both make the particles; give one"},
      {"      wall_layer: membrane\n", "      wall_layer: channel\n",
       "name 'channel' is already used"},
      {"{type: ellipse, center: [0.7, 0.5], radii: [0.2, 0.15]}", "{type: union, shapes: []}",
       "'union' of nothing; required: 'shapes', a list of at least 1 shapes"},
      {"{type: ellipse, center: [0.7, 0.5], radii: [0.2, 0.15]}", "{type: mesh, file: missing.stl}",
       "missing.stl: cannot open the mesh file"},
      {"{type: ellipse, center: [0.7, 0.5], radii: [0.2, 0.15]}",
       "{type: disk, center: [0.7, 0.5], radius: 0.2, rotate: {axis: [0, 0, 1], angle: 5}}",
       "expected an angle in degrees"},
      {"      role: solid\n", "      role: fluid\n", "a second fluid body; allowed: one"},
      {"backend: static, h_over_dx: 3.0", "backend: static, h_over_dx: 3.0, wall_model: morris",
       "unknown wall model 'morris'"},
  };
  for (const auto& c : cases) {
    const std::string msg = error_of(replace_once(kChannel, c.from, c.to));
    EXPECT_NE(msg.find(c.expected), std::string::npos) << c.to << "\n" << msg;
  }
}

TEST(SceneGeometry, ThinSolidIsWarned) {
  const std::string text =
      replace_once(kChannel, "{type: ellipse, center: [0.7, 0.5], radii: [0.2, 0.15]}",
                   "{type: box, lower: [0.7, 0.2], upper: [0.76, 0.8]}");
  const Scene s = parse_scene(text, "scene.yaml");
  ASSERT_FALSE(s.warnings.empty());
  EXPECT_NE(s.warnings[0].find("scene.yaml:11:14: geometry.bodies[1].shape: solid 'cell' is"),
            std::string::npos)
      << s.warnings[0];
  EXPECT_NE(s.warnings[0].find("thinner than the kernel support"), std::string::npos);
  EXPECT_LT(s.geometry->smallest_feature, 0.15);
}

}  // namespace
}  // namespace sadr::orchestrator
