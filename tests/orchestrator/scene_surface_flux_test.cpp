// SPDX-License-Identifier: MIT
// Scene `boundary_fluxes` with `surface`: the first fluid layer next to a surface of the
// geometry section, shares summing to the surface's exact area (a disk, a sphere, a fluid
// body's own boundary) or to the layer's estimate (a CSG solid), and the refusals with
// file:line.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <numeric>
#include <string>

#include "sadr/common/status.hpp"
#include "sadr/orchestrator/scene_loader.hpp"
#include "scene_test_support.hpp"

namespace sadr::orchestrator {
namespace {

using test::replace_once;
constexpr double kPi = std::numbers::pi;

// A 2 x 2 closed box of fluid around a solid disk of radius 0.3, dx = 0.05; a region body.
const std::string kDisk =
    "dimension: 2\n"                                                                       // 1
    "box: {lower: [0.0, 0.0], upper: [2.0, 2.0]}\n"                                        // 2
    "geometry:\n"                                                                          // 3
    "  spacing: 0.05\n"                                                                    // 4
    "  bodies:\n"                                                                          // 5
    "    - {name: tank, role: fluid, shape: {type: box, lower: [0.1, 0.1], upper: "        // 6
    "[1.9, 1.9]}}\n"                                                                       //
    "    - {name: cell, role: solid, shape: {type: disk, center: [1.0, 1.0], radius: "     // 7
    "0.3}}\n"                                                                              //
    "    - {name: spot, role: region, shape: {type: disk, center: [0.5, 0.5], radius: "    // 8
    "0.2}}\n"                                                                              //
    "fluid: {backend: static, h_over_dx: 2.0}\n"                                           // 9
    "species:\n"                                                                           // 10
    "  - {name: A, stochastic: false, diffusivity: 0.1}\n"                                 // 11
    "  - {name: B, diffusivity: 0.1}\n"                                                    // 12
    "boundary_fluxes:\n"                                                                   // 13
    "  - {name: release, species: A, surface: cell, law: {type: expression, expression: "  // 14
    "\"2\"}}\n"                                                                            //
    "time: {coupling_step: 0.1, end: 1.0}\n";                                              // 15

const std::string kLine14 =
    "  - {name: release, species: A, surface: cell, law: {type: expression, expression: "
    "\"2\"}}\n";

std::string error_of(const std::string& text) {
  try {
    (void)parse_scene(text, "scene.yaml");
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "<no error>";
}

double sum(const std::vector<double>& v) {
  return std::accumulate(v.begin(), v.end(), 0.0);
}

/// Checks that every member of the layer is a fluid particle within one spacing dx of the
/// innermost member's distance from the circle or sphere (centre c, radius r; the fluid
/// outside it when `outside`) and returns their number.
std::size_t check_ring(const Scene& s, const Reaction& rx, std::array<double, 3> c, double r,
                       double dx, bool outside) {
  std::vector<double> gaps;
  for (const auto i : rx.boundary_particles) {
    EXPECT_EQ(s.particles.kind(i), ParticleKind::kFluid);
    double d2 = 0;
    for (int a = 0; a < s.box.dimension; ++a) {
      const double x = s.particles.positions[3 * i + a] - c[a];
      d2 += x * x;
    }
    gaps.push_back(outside ? std::sqrt(d2) - r : r - std::sqrt(d2));
  }
  const double first = *std::min_element(gaps.begin(), gaps.end());
  EXPECT_GT(first, 0.0);
  EXPECT_LT(first, 0.5 * dx);
  for (const double g : gaps) EXPECT_LT(g, first + dx);
  return rx.boundary_particles.size();
}

TEST(SurfaceFluxScene, TheLayerAroundADiskSharesItsExactPerimeter) {
  const Scene s = parse_scene(kDisk, "scene.yaml");
  ASSERT_EQ(s.warnings.size(), 1U);  // only that species B stays zero
  EXPECT_NE(s.warnings[0].find("'B' is zero everywhere"), std::string::npos) << s.warnings[0];
  ASSERT_EQ(s.reactions.size(), 1u);
  const Reaction& rx = s.reactions[0];
  EXPECT_FALSE(rx.stochastic);
  const std::size_t n = check_ring(s, rx, {1, 1, 0}, 0.3, 0.05, true);
  // The ring of width dx outside r = 0.3 holds pi ((0.35)^2 - 0.3^2) / dx^2 = 40.8 sites on
  // average; the lattice gives a few more or fewer.
  EXPECT_GT(n, 30u);
  EXPECT_LT(n, 52u);
  ASSERT_EQ(rx.boundary_areas.size(), n);
  EXPECT_NEAR(sum(rx.boundary_areas), 2 * kPi * 0.3, 1e-12);
  for (const double a : rx.boundary_areas) EXPECT_GT(a, 0.0);
  // Every fluid particle nearer to the disk than the layer's innermost one plus dx is in it:
  // none is left out between the layer and the surface.
  std::vector<bool> in(s.particles.size(), false);
  for (const auto i : rx.boundary_particles) in[i] = true;
  for (std::size_t i = 0; i < s.particles.size(); ++i) {
    if (s.particles.kind(i) != ParticleKind::kFluid) continue;
    const double dx = s.particles.positions[3 * i] - 1, dy = s.particles.positions[3 * i + 1] - 1;
    if (std::hypot(dx, dy) - 0.3 < 0.5 * 0.05) {
      EXPECT_TRUE(in[i]) << i;
    }
  }
}

TEST(SurfaceFluxScene, ASphereAndAFluidBodysOwnBoundaryShareTheirExactAreas) {
  // 3D: a solid sphere of radius 0.25 in a unit box of fluid, dx = 0.05.
  const std::string sphere =
      "dimension: 3\n"
      "box: {lower: [0, 0, 0], upper: [1, 1, 1]}\n"
      "geometry:\n"
      "  spacing: 0.05\n"
      "  bodies:\n"
      "    - {name: ball, role: solid, shape: {type: sphere, center: [0.5, 0.5, 0.5], radius: "
      "0.25}}\n"
      "fluid: {backend: static, h_over_dx: 2.0}\n"
      "species:\n"
      "  - {name: B, diffusivity: 0.1}\n"
      "boundary_fluxes:\n"
      "  - {species: B, surface: ball, law: {type: expression, expression: \"3\"}}\n"
      "time: {coupling_step: 0.1, end: 1.0}\n";
  const Scene s = parse_scene(sphere, "scene.yaml");
  ASSERT_EQ(s.reactions.size(), 1u);
  EXPECT_TRUE(s.reactions[0].stochastic);
  const std::size_t n = check_ring(s, s.reactions[0], {0.5, 0.5, 0.5}, 0.25, 0.05, true);
  // The shell of width dx: 4/3 pi (0.3^3 - 0.25^3) / dx^3 = 381 sites on average.
  EXPECT_GT(n, 300u);
  EXPECT_LT(n, 460u);
  EXPECT_NEAR(sum(s.reactions[0].boundary_areas), 4 * kPi * 0.25 * 0.25, 1e-12);

  // 2D: the fluid is a disk of radius 0.8; the flux enters through its boundary from outside.
  const std::string inside = replace_once(
      replace_once(kDisk,
                   "    - {name: tank, role: fluid, shape: {type: box, lower: [0.1, 0.1], upper: "
                   "[1.9, 1.9]}}\n",
                   "    - {name: tank, role: fluid, shape: {type: disk, center: [1.0, 1.0], "
                   "radius: 0.8}}\n"),
      "surface: cell", "surface: tank");
  const Scene t = parse_scene(inside, "scene.yaml");
  const std::size_t m = check_ring(t, t.reactions[0], {1, 1, 0}, 0.8, 0.05, false);
  EXPECT_GT(m, 80u);  // pi (0.8^2 - 0.75^2) / dx^2 = 97.4 on average
  EXPECT_LT(m, 115u);
  EXPECT_NEAR(sum(t.reactions[0].boundary_areas), 2 * kPi * 0.8, 1e-12);
}

TEST(SurfaceFluxScene, ACsgSolidSharesTheLayersEstimateOfItsArea) {
  // A union of two overlapping disks of radius 0.3, centres 0.3 apart: no closed form in the
  // shape, so A = sum l_i^(d-1) over the layer. The true perimeter: 2 (2 pi - 2 acos(1/2)) r
  // = 2 (2 pi - 2 pi / 3) 0.3 = 8 pi / 3 * 0.3.
  const std::string csg = replace_once(
      kDisk, "shape: {type: disk, center: [1.0, 1.0], radius: 0.3}}\n",
      "shape: {type: union, shapes: [{type: disk, center: [0.85, 1.0], radius: 0.3}, {type: "
      "disk, center: [1.15, 1.0], radius: 0.3}]}}\n");
  const Scene s = parse_scene(csg, "scene.yaml");
  ASSERT_EQ(s.warnings.size(), 2U);  // the area, and species B that stays zero
  EXPECT_NE(s.warnings[1].find("scene.yaml:14:"), std::string::npos) << s.warnings[1];
  EXPECT_NE(s.warnings[1].find("not known in closed form"), std::string::npos) << s.warnings[1];
  const Reaction& rx = s.reactions[0];
  double own = 0;
  for (const auto i : rx.boundary_particles) own += std::sqrt(s.particles.volume(i));
  EXPECT_NEAR(sum(rx.boundary_areas), own, 1e-12 * own);
  const double exact = 8 * kPi / 3 * 0.3;
  // The lattice's estimate: the ring one spacing wide outside a convex outline holds
  // (P + pi dx) / dx sites on average, and a circle of radius 6 dx centred on the lattice holds
  // more than that (measured: 3.0 against 2.513, +19 %).
  EXPECT_NEAR(own / exact, 1.0, 0.25);
  std::printf("CSG perimeter: layer estimate %.6g, exact %.6g\n", own, exact);
}

TEST(SurfaceFluxScene, WrongSurfacesAreRefusedWithFileAndLine) {
  struct Case {
    std::string to;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {"  - {species: A, surface: cel, law: {type: expression, expression: \"2\"}}\n",
       "scene.yaml:14:27: boundary_fluxes[0].surface: unknown surface 'cel'; did you mean "
       "'cell'? (allowed: the fluid and solid bodies of 'geometry': tank, cell)"},
      {"  - {species: A, surface: spot, law: {type: expression, expression: \"2\"}}\n",
       "scene.yaml:14:27: boundary_fluxes[0].surface: 'spot' is a region body, which has no "
       "surface"},
      {"  - {species: A, surface: cell, face: x-, law: {type: expression, expression: \"2\"}}\n",
       "scene.yaml:14:27: boundary_fluxes[0].surface: give either 'face'"},
      {"  - {species: A, law: {type: expression, expression: \"2\"}}\n",
       "scene.yaml:14:5: boundary_fluxes[0]: missing 'face' or 'surface'"},
      {"  - {species: A, surface: cell, region: spot, law: {type: expression, expression: "
       "\"2\"}}\n",
       "scene.yaml:14:41: boundary_fluxes[0].region: boundary flux 'flux0': no particle of the "
       "first fluid layer next to 'cell' lies in region 'spot'"},
      {"  - {species: A, surface: [cell], law: {type: expression, expression: \"2\"}}\n",
       "scene.yaml:14:27: boundary_fluxes[0].surface:"},
  };
  for (const auto& c : cases) {
    const std::string msg = error_of(replace_once(kDisk, kLine14, c.to));
    EXPECT_NE(msg.find(c.expected), std::string::npos) << c.to << "\n" << msg;
  }
  // A scene without a geometry section.
  const std::string lattice =
      "dimension: 2\n"
      "box: {lower: [0, 0], upper: [1, 1]}\n"
      "particles: {spacing: 0.1}\n"
      "fluid: {backend: static, h_over_dx: 2.0}\n"
      "species: [{name: B, diffusivity: 0.1}]\n"
      "boundary_fluxes:\n"
      "  - {species: B, surface: cell, law: {type: expression, expression: \"1\"}}\n"
      "time: {coupling_step: 0.1, end: 1.0}\n";
  const std::string msg = error_of(lattice);
  EXPECT_NE(msg.find("scene.yaml:7:27: boundary_fluxes[0].surface: 'surface' names a fluid or "
                     "solid body of the 'geometry' section, and the scene has none"),
            std::string::npos)
      << msg;
}

}  // namespace
}  // namespace sadr::orchestrator
