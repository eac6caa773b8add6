// SPDX-License-Identifier: MIT
// Scene `boundary_fluxes` on a part of a body's surface: `group` (a physical group of a mesh
// body's .msh file: shares summing to the group's exact length or area, particles next to that
// group only, transforms followed) and `region` with `surface` (the part of the layer in the
// region, with the shares it had), and the refusals with file:line.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numeric>
#include <string>

#include "sadr/common/status.hpp"
#include "sadr/orchestrator/scene_loader.hpp"
#include "scene_test_support.hpp"

namespace sadr::orchestrator {
namespace {

using test::replace_once;

// A 2D quadrilateral channel (0,0) (2,0) (2,1) (0,1.2), three triangles: physical curves
// "inlet" (x = 0, two segments, length 1.2), "outlet" (x = 2, length 1), "walls" (bottom and
// top), a point "corner" and the surface "channel".
const std::string kChannelMsh =
    "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
    "$PhysicalNames\n5\n0 5 \"corner\"\n1 1 \"inlet\"\n1 2 \"outlet\"\n1 3 \"walls\"\n"
    "2 4 \"channel\"\n$EndPhysicalNames\n"
    "$Nodes\n5\n1 0 0 0\n2 2 0 0\n3 2 1 0\n4 0 1.2 0\n5 0 0.5 0\n$EndNodes\n"
    "$Elements\n9\n"
    "1 15 2 5 5 1\n"
    "2 1 2 1 1 1 5\n3 1 2 1 1 5 4\n4 1 2 2 2 2 3\n5 1 2 3 3 1 2\n6 1 2 3 3 3 4\n"
    "7 2 2 4 4 1 2 5\n8 2 2 4 4 5 2 3\n9 2 2 4 4 5 3 4\n"
    "$EndElements\n";

const std::string kChannel =
    "dimension: 2\n"                                                                      // 1
    "box: {lower: [-0.5, -0.5], upper: [2.5, 1.7]}\n"                                     // 2
    "geometry:\n"                                                                         // 3
    "  spacing: 0.05\n"                                                                   // 4
    "  bodies:\n"                                                                         // 5
    "    - {name: duct, role: fluid, shape: {type: mesh, file: channel.msh}}\n"           // 6
    "fluid: {backend: static, h_over_dx: 2.0}\n"                                          // 7
    "species:\n"                                                                          // 8
    "  - {name: A, stochastic: false, diffusivity: 0.1}\n"                                // 9
    "boundary_fluxes:\n"                                                                  // 10
    "  - {name: feed, species: A, surface: duct, group: inlet, law: {type: expression, "  // 11
    "expression: \"2\"}}\n"                                                               //
    "time: {coupling_step: 0.1, end: 1.0}\n";                                             // 12

struct GroupDir {
  std::filesystem::path path;
  GroupDir() {
    path = std::filesystem::temp_directory_path() /
           ("sadr_surface_group_test_" + std::to_string(::getpid()));
    std::filesystem::create_directories(path);
  }
  ~GroupDir() { std::filesystem::remove_all(path); }
  void write(const std::string& name, const std::string& text) const {
    std::ofstream(path / name) << text;
  }
};

double total(const std::vector<double>& v) {
  return std::accumulate(v.begin(), v.end(), 0.0);
}

Scene channel(const GroupDir& dir, const std::string& text) {
  dir.write("channel.msh", kChannelMsh);
  return parse_scene(text, dir.path / "scene.yaml");
}

std::string channel_error(const GroupDir& dir, const std::string& text) {
  try {
    (void)channel(dir, text);
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "<no error>";
}

TEST(SurfaceGroupFlux, EachGroupOfA2dChannelSharesItsExactLength) {
  GroupDir dir;
  const std::string groups = replace_once(
      kChannel, "time:",
      "  - {species: A, surface: duct, group: outlet, law: {type: expression, expression: "
      "\"1\"}}\n"
      "  - {species: A, surface: duct, group: walls, law: {type: expression, expression: "
      "\"1\"}}\n"
      "  - {species: A, surface: duct, law: {type: expression, expression: \"1\"}}\n"
      "time:");
  const Scene s = channel(dir, groups);
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  ASSERT_EQ(s.reactions.size(), 4U);
  const auto& inlet = s.reactions[0];
  const auto& outlet = s.reactions[1];
  const auto& walls = s.reactions[2];
  const auto& whole = s.reactions[3];
  const double top = std::hypot(2.0, 0.2);
  EXPECT_NEAR(total(inlet.boundary_areas), 1.2, 1e-12);
  EXPECT_NEAR(total(outlet.boundary_areas), 1.0, 1e-12);
  EXPECT_NEAR(total(walls.boundary_areas), 2.0 + top, 1e-12);
  EXPECT_NEAR(total(whole.boundary_areas), 4.2 + top, 1e-12);
  // The inlet's layer is the column of sites at x = 0.025 (24 between y = 0 and 1.2, the top one
  // nearer to the top wall); the outlet's at x = 1.975 (20). A corner site as near to two groups
  // belongs to both.
  EXPECT_GE(inlet.boundary_particles.size(), 23U);
  EXPECT_LE(inlet.boundary_particles.size(), 25U);
  EXPECT_GE(outlet.boundary_particles.size(), 20U);
  EXPECT_LE(outlet.boundary_particles.size(), 21U);
  for (const auto i : inlet.boundary_particles) {
    EXPECT_EQ(s.particles.kind(i), ParticleKind::kFluid);
    EXPECT_NEAR(s.particles.positions[3 * i], 0.025, 1e-12) << i;
  }
  for (const auto i : outlet.boundary_particles) {
    EXPECT_NEAR(s.particles.positions[3 * i], 1.975, 1e-12) << i;
  }
  for (const auto i : walls.boundary_particles) {  // next to the bottom or the top
    const double x = s.particles.positions[3 * i], y = s.particles.positions[3 * i + 1];
    const double to_top = (1.2 - 0.1 * x - y) / std::hypot(1.0, 0.1);
    EXPECT_TRUE(y < 0.05 || to_top < 0.075 + 1e-9) << x << " " << y;
  }
}

TEST(SurfaceGroupFlux, TransformsMoveTheGroupWithTheBody) {
  GroupDir dir;
  // Scaled by 0.5, then moved by (0.3, 0.2): the inlet is x = 0.3, y in [0.2, 0.8].
  const std::string moved = replace_once(kChannel, "file: channel.msh}",
                                         "file: channel.msh, scale: 0.5, translate: [0.3, 0.2]}");
  const Scene s = channel(dir, moved);
  ASSERT_EQ(s.reactions.size(), 1U);
  const auto& rx = s.reactions[0];
  EXPECT_NEAR(total(rx.boundary_areas), 0.6, 1e-12);
  for (const auto i : rx.boundary_particles) {
    EXPECT_NEAR(s.particles.positions[3 * i], 0.325, 1e-12) << i;
    EXPECT_GT(s.particles.positions[3 * i + 1], 0.2);
    EXPECT_LT(s.particles.positions[3 * i + 1], 0.8);
  }
  EXPECT_GE(rx.boundary_particles.size(), 11U);  // 12 sites, the top one nearer the wall
  EXPECT_LE(rx.boundary_particles.size(), 13U);
}

TEST(SurfaceGroupFlux, APatchOfA3dMeshSharesItsExactArea) {
  // The cube [0.3, 0.7]^3 as 12 triangles: physical surfaces "lid" (z = 0.7) and "sides".
  const std::string msh =
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
      "$PhysicalNames\n2\n2 1 \"lid\"\n2 2 \"sides\"\n$EndPhysicalNames\n"
      "$Nodes\n8\n1 0.3 0.3 0.3\n2 0.7 0.3 0.3\n3 0.7 0.7 0.3\n4 0.3 0.7 0.3\n"
      "5 0.3 0.3 0.7\n6 0.7 0.3 0.7\n7 0.7 0.7 0.7\n8 0.3 0.7 0.7\n$EndNodes\n"
      "$Elements\n12\n"
      "1 2 2 1 1 5 6 7\n2 2 2 1 1 5 7 8\n"
      "3 2 2 2 2 1 3 2\n4 2 2 2 2 1 4 3\n5 2 2 2 2 1 2 6\n6 2 2 2 2 1 6 5\n"
      "7 2 2 2 2 2 3 7\n8 2 2 2 2 2 7 6\n9 2 2 2 2 3 4 8\n10 2 2 2 2 3 8 7\n"
      "11 2 2 2 2 4 1 5\n12 2 2 2 2 4 5 8\n"
      "$EndElements\n";
  const std::string scene =
      "dimension: 3\n"
      "box: {lower: [0, 0, 0], upper: [1, 1, 1]}\n"
      "geometry:\n"
      "  spacing: 0.05\n"
      "  bodies:\n"
      "    - {name: block, role: solid, shape: {type: mesh, file: cube.msh}}\n"
      "fluid: {backend: static, h_over_dx: 2.0}\n"
      "species: [{name: B, diffusivity: 0.1}]\n"
      "boundary_fluxes:\n"
      "  - {species: B, surface: block, group: lid, law: {type: expression, expression: "
      "\"3\"}}\n"
      "  - {species: B, surface: block, group: sides, law: {type: expression, expression: "
      "\"3\"}}\n"
      "time: {coupling_step: 0.1, end: 1.0}\n";
  GroupDir dir;
  dir.write("cube.msh", msh);
  const Scene s = parse_scene(scene, dir.path / "scene.yaml");
  ASSERT_EQ(s.reactions.size(), 2U);
  const auto& lid = s.reactions[0];
  EXPECT_NEAR(total(lid.boundary_areas), 0.16, 1e-12);
  EXPECT_NEAR(total(s.reactions[1].boundary_areas), 5 * 0.16, 1e-12);
  // Above the lid: its 8 x 8 sites, and the rim's 4 x 8 + 4 as near to the lid as to a side.
  EXPECT_GE(lid.boundary_particles.size(), 64U);
  EXPECT_LE(lid.boundary_particles.size(), 100U);
  std::size_t above = 0;
  for (const auto i : lid.boundary_particles) {
    const double* x = &s.particles.positions[3 * i];
    EXPECT_NEAR(x[2], 0.725, 1e-12) << i;
    above += x[0] > 0.3 && x[0] < 0.7 && x[1] > 0.3 && x[1] < 0.7;
  }
  EXPECT_EQ(above, 64U);
}

TEST(SurfaceGroupFlux, ARegionKeepsItsPartOfTheLayerWithItsShares) {
  GroupDir dir;
  // The whole surface, and the part of it whose layer lies in the lower half (y < 0.6).
  const std::string text = replace_once(
      replace_once(kChannel, "geometry:",
                   "regions: [{name: low, shape: box, lower: [-0.5, -0.5], upper: [2.5, 0.6]}]\n"
                   "geometry:"),
      "  - {name: feed, species: A, surface: duct, group: inlet,",
      "  - {name: all_round, species: A, surface: duct, law: {type: expression, expression: "
      "\"1\"}}\n"
      "  - {name: feed, species: A, surface: duct, region: low,");
  const Scene s = channel(dir, text);
  ASSERT_EQ(s.reactions.size(), 2U);
  const auto& whole = s.reactions[0];
  const auto& part = s.reactions[1];
  ASSERT_LT(part.boundary_particles.size(), whole.boundary_particles.size());
  ASSERT_FALSE(part.boundary_particles.empty());
  for (std::size_t k = 0; k < part.boundary_particles.size(); ++k) {
    const auto i = part.boundary_particles[k];
    EXPECT_LT(s.particles.positions[3 * i + 1], 0.6);
    const auto it = std::find(whole.boundary_particles.begin(), whole.boundary_particles.end(), i);
    ASSERT_NE(it, whole.boundary_particles.end());
    EXPECT_EQ(
        part.boundary_areas[k],
        whole.boundary_areas[static_cast<std::size_t>(it - whole.boundary_particles.begin())]);
  }
  // The part: the bottom wall (2), the inlet and outlet below y = 0.6 (0.6 + 0.6), a spacing of
  // rounding at most at either cut.
  EXPECT_NEAR(total(part.boundary_areas), 3.2, 0.15);
}

TEST(SurfaceGroupFlux, WrongGroupsAreRefusedWithFileAndLine) {
  struct Case {
    std::string from, to, expected;
  };
  const std::string group = "group: inlet,";
  const std::vector<Case> cases = {
      {group, "group: inlt,",
       "scene.yaml:11:52: boundary_fluxes[0].group: no physical group named 'inlt' in "},
      {group, "group: inlt,",
       "did you mean 'inlet'? (allowed: the groups of dimension 1: inlet, outlet, walls)"},
      {group, "group: channel,", "boundary_fluxes[0].group: physical group 'channel' of "},
      {group, "group: channel,",
       "has dimension 2; a part of the surface of a 2D body is a curve (dimension 1: line "
       "segments) (allowed: the groups of dimension 1: inlet, outlet, walls)"},
      {group, "group: corner,", "physical group 'corner' of "},
      {group, "group: corner,", "has dimension 0"},
      {"{type: mesh, file: channel.msh}", "{type: box, lower: [0, 0], upper: [2, 1.2]}",
       "scene.yaml:11:52: boundary_fluxes[0].group: 'group' names a physical group of a mesh "
       "file, and the shape of 'duct' is not a mesh"},
      {"surface: duct, group: inlet,", "face: x-, group: inlet,",
       "boundary_fluxes[0].group: 'group' names a part of a body's surface and needs 'surface'"},
  };
  GroupDir dir;
  for (const auto& c : cases) {
    const std::string msg = channel_error(dir, replace_once(kChannel, c.from, c.to));
    EXPECT_NE(msg.find(c.expected), std::string::npos) << c.to << "\n" << msg;
  }
}

TEST(SurfaceGroupFlux, AGroupWithNoFluidNextToItIsRefused) {
  // A solid block covers the outlet: no fluid particle is nearer to it than to the walls.
  GroupDir dir;
  const std::string covered = replace_once(
      kChannel, "    - {name: duct, role: fluid, shape: {type: mesh, file: channel.msh}}\n",
      "    - {name: duct, role: fluid, shape: {type: mesh, file: channel.msh}}\n"
      "    - {name: plug, role: solid, shape: {type: box, lower: [1.5, -0.2], upper: [2.2, "
      "1.5]}}\n");
  const std::string msg =
      channel_error(dir, replace_once(covered, "group: inlet,", "group: outlet,"));
  EXPECT_NE(msg.find("scene.yaml:12:52: boundary_fluxes[0].group: boundary flux 'feed' on group "
                     "'outlet' of 'duct': no fluid particle lies next to the surface's part"),
            std::string::npos)
      << msg;
}

// Species `boundaries` with `surface` and `group`: the wall particles behind one physical group.
const std::string kWalled =
    "dimension: 2\n"                                                             // 1
    "box: {lower: [-0.5, -0.5], upper: [2.5, 1.7]}\n"                            // 2
    "geometry:\n"                                                                // 3
    "  spacing: 0.05\n"                                                          // 4
    "  bodies:\n"                                                                // 5
    "    - {name: duct, role: fluid, shape: {type: mesh, file: channel.msh}}\n"  // 6
    "fluid: {backend: static, h_over_dx: 2.0}\n"                                 // 7
    "species:\n"                                                                 // 8
    "  - name: A\n"                                                              // 9
    "    stochastic: false\n"                                                    // 10
    "    diffusivity: 0.1\n"                                                     // 11
    "    boundaries:\n"                                                          // 12
    "      - {surface: duct, group: inlet, condition: dirichlet, value: 1}\n"    // 13
    "      - {surface: duct, group: outlet, condition: dirichlet, value: 0}\n"   // 14
    "time: {coupling_step: 0.1, end: 1.0}\n";                                    // 15

/// Distance from p to the segment a-b (2D).
double to_segment(double px, double py, double ax, double ay, double bx, double by) {
  const double ux = bx - ax, uy = by - ay;
  const double t = std::clamp(((px - ax) * ux + (py - ay) * uy) / (ux * ux + uy * uy), 0.0, 1.0);
  return std::hypot(px - ax - t * ux, py - ay - t * uy);
}

/// The channel's groups measured from p: inlet, outlet, walls (bottom and top).
std::array<double, 3> group_distances(double x, double y) {
  return {to_segment(x, y, 0, 0, 0, 1.2), to_segment(x, y, 2, 0, 2, 1),
          std::min(to_segment(x, y, 0, 0, 2, 0), to_segment(x, y, 2, 1, 0, 1.2))};
}

std::vector<std::uint32_t> region_particles(const Scene& s, const std::string& name) {
  const Region* r = s.find_region(name);
  return r ? r->particles : std::vector<std::uint32_t>{};
}

TEST(SurfaceGroupBoundary, EachGroupHoldsExactlyTheWallsBehindIt) {
  GroupDir dir;
  const std::string text = replace_once(
      kWalled, "time:",
      "  - name: B\n"
      "    diffusivity: 0.1\n"
      "    boundaries: [{surface: duct, group: walls, condition: dirichlet, value: 2}]\n"
      "  - name: W\n"
      "    diffusivity: 0.1\n"
      "    boundaries: [{surface: duct, condition: dirichlet, value: 3}]\n"
      "time:");
  const Scene s = channel(dir, text);
  ASSERT_EQ(s.species.size(), 3U);
  ASSERT_EQ(s.species[0].boundaries.size(), 2U);
  EXPECT_EQ(s.species[0].boundaries[0].region, "duct/inlet");
  EXPECT_EQ(s.species[0].boundaries[1].region, "duct/outlet");
  EXPECT_EQ(s.species[1].boundaries[0].region, "duct/walls");
  EXPECT_EQ(s.species[2].boundaries[0].region, "duct/surface");
  const auto inlet = region_particles(s, "duct/inlet");
  const auto outlet = region_particles(s, "duct/outlet");
  const auto walls = region_particles(s, "duct/walls");
  const auto whole = region_particles(s, "duct/surface");
  // Independently: every wall particle, and the groups it is no farther from than from the rest.
  const ParticleState& p = s.particles;
  std::array<std::vector<std::uint32_t>, 3> expected;
  std::vector<std::uint32_t> all_walls;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kind(i) != ParticleKind::kWall) continue;
    all_walls.push_back(static_cast<std::uint32_t>(i));
    const auto d = group_distances(p.positions[3 * i], p.positions[3 * i + 1]);
    const double nearest = std::min({d[0], d[1], d[2]});
    for (std::size_t g = 0; g < 3; ++g) {
      if (d[g] <= nearest + 1e-9) expected[g].push_back(static_cast<std::uint32_t>(i));
    }
  }
  EXPECT_EQ(inlet, expected[0]);
  EXPECT_EQ(outlet, expected[1]);
  EXPECT_EQ(walls, expected[2]);
  EXPECT_EQ(whole, all_walls);  // the walls behind the whole surface: every wall layer
  // Behind the inlet (x < 0, two wall layers at x = -0.025 and -0.075): its 24 rows of sites in
  // 0 < y < 1.2, and the corner sites as near to the inlet as to the walls, behind both.
  std::size_t rows = 0, corner = 0;
  for (const auto i : inlet) {
    const double x = p.positions[3 * i], y = p.positions[3 * i + 1];
    EXPECT_LT(x, 0.0) << i;
    EXPECT_GT(x, -0.1) << i;
    const bool in_extent = y > 0.0 && y < 1.2;
    rows += in_extent;
    const bool shared = std::binary_search(walls.begin(), walls.end(), i);
    EXPECT_EQ(shared, !in_extent) << x << " " << y;
    corner += shared;
  }
  EXPECT_EQ(rows, 48U);
  EXPECT_EQ(corner, 2U);  // (-0.025, -0.025) and (-0.025, 1.225)
  EXPECT_EQ(inlet.size(), 50U);
  for (const auto i : outlet) {
    EXPECT_GT(p.positions[3 * i], 2.0) << i;
    EXPECT_FALSE(std::binary_search(inlet.begin(), inlet.end(), i)) << i;
  }
  std::printf("walls behind inlet %zu (%zu at the corners), outlet %zu, walls %zu, whole %zu\n",
              inlet.size(), corner, outlet.size(), walls.size(), whole.size());
  // The Dirichlet values start on those walls only.
  const auto& a = s.species[0].initial;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const bool in_inlet = std::binary_search(inlet.begin(), inlet.end(), i);
    EXPECT_EQ(a[i], in_inlet ? 1.0 : 0.0) << i;
  }
}

TEST(SurfaceGroupBoundary, ACornerWallStaysWithTheFirstGroupListed) {
  GroupDir dir;
  // The inlet held at 1, the walls with an inward flux: the corner sites behind both keep the
  // inlet's condition (listed first) instead of being refused as an overlap.
  const std::string text = replace_once(kWalled, "group: outlet, condition: dirichlet, value: 0}",
                                        "group: walls, condition: neumann, value: 0.5}");
  const Scene s = channel(dir, text);
  ASSERT_EQ(s.species[0].boundaries.size(), 2U);
  EXPECT_EQ(s.species[0].boundaries[1].region, "duct/walls");
  const auto inlet = region_particles(s, "duct/inlet");
  const auto walls = region_particles(s, "duct/walls");
  ASSERT_FALSE(walls.empty());
  std::vector<std::uint32_t> both;
  std::set_intersection(inlet.begin(), inlet.end(), walls.begin(), walls.end(),
                        std::back_inserter(both));
  EXPECT_TRUE(both.empty());
  for (const auto i : walls) {  // behind the bottom or the top, none at x < 0
    EXPECT_GT(s.particles.positions[3 * i], 0.0) << i;
  }
}

TEST(SurfaceGroupBoundary, WrongSurfacesAndGroupsAreRefusedWithFileAndLine) {
  struct Case {
    std::string from, to, expected;
  };
  const std::string group = "group: inlet,";
  const std::vector<Case> cases = {
      {group, "group: inlt,",
       "scene.yaml:13:32: species[0].boundaries[0].group: no physical group named 'inlt' in "},
      {group, "group: inlt,",
       "did you mean 'inlet'? (allowed: the groups of dimension 1: inlet, outlet, walls)"},
      {group, "group: channel,", "species[0].boundaries[0].group: physical group 'channel' of "},
      {group, "group: channel,", "has dimension 2; a part of the surface of a 2D body is a curve"},
      {group, "group: corner,", "has dimension 0"},
      {"{type: mesh, file: channel.msh}", "{type: box, lower: [0, 0], upper: [2, 1.2]}",
       "scene.yaml:13:32: species[0].boundaries[0].group: 'group' names a physical group of a "
       "mesh file, and the shape of 'duct' is not a mesh"},
      {"{surface: duct, group: inlet,", "{group: inlet,",
       "scene.yaml:13:17: species[0].boundaries[0].group: 'group' names a part of a body's "
       "surface and needs 'surface'"},
      {"{surface: duct, group: inlet,", "{region: all, surface: duct, group: inlet,",
       "species[0].boundaries[0].surface: give either 'region'"},
      {"{surface: duct, group: inlet,", "{surface: dcut, group: inlet,",
       "scene.yaml:13:19: species[0].boundaries[0].surface: unknown surface 'dcut'; did you mean "
       "'duct'?"},
      {"{surface: duct, group: inlet, condition: dirichlet, value: 1}",
       "{surface: duct, group: inlet, condition: inflow, value: 1}",
       "species[0].boundaries[0].surface: condition 'inflow' needs a region of shape box or "
       "channel"},
      {"group: outlet, condition: dirichlet, value: 0}", "condition: dirichlet, value: 0}",
       "species[0].boundaries[1].surface: the walls behind 'duct/surface' overlap the region of "
       "species[0].boundaries[0]"},
      {"spacing: 0.05\n", "spacing: 0.05\n  wall_depth: 0\n",
       "species[0].boundaries[0].group: no wall particle lies behind group 'inlet' of 'duct'"},
  };
  GroupDir dir;
  for (const auto& c : cases) {
    const std::string msg = channel_error(dir, replace_once(kWalled, c.from, c.to));
    EXPECT_NE(msg.find(c.expected), std::string::npos) << c.to << "\n" << msg;
  }
}

TEST(SurfaceGroupBoundary, AGroupWithNoWallsOfItsOwnIsRefused) {
  GroupDir dir;
  // The walls listed first hold the corner sites; the inlet without them still has its own.
  // A group listed twice has none left the second time.
  const std::string text = replace_once(kWalled, "group: outlet,", "group: inlet,");
  const std::string msg = channel_error(dir, text);
  EXPECT_NE(msg.find("scene.yaml:14:32: species[0].boundaries[1].group: every wall particle "
                     "behind group 'inlet' of 'duct' is held by an earlier entry's group"),
            std::string::npos)
      << msg;
}

}  // namespace
}  // namespace sadr::orchestrator
