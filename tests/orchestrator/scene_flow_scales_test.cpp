// SPDX-License-Identifier: MIT
// The sound speed and background pressure the loader chooses when a scene leaves them out, and
// the warnings where given values break the rules (scene_flow_scales.cpp; docs/scene-format.md,
// "Sound speed and background pressure").
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "sadr/common/status.hpp"
#include "sadr/orchestrator/scene_loader.hpp"
#include "scene_test_support.hpp"

namespace sadr::orchestrator {
namespace {

using test::replace_once;

/// A periodic 2D channel (walls below y = 0 and above y = 1) driven by g = 2 along x, with a
/// disk of wall particles in it: the obstacle scene of docs/how-to-obstacle.md, fluid settings
/// left out.
const std::string kObstacle =
    "dimension: 2\n"                                                                     // 1
    "box: {lower: [0.0, -0.175], upper: [2.0, 1.175], periodic: [true, false]}\n"        // 2
    "regions:\n"                                                                         // 3
    "  - {name: lower_wall, shape: channel, axis: y, lower: -1.0, upper: 0.0}\n"         // 4
    "  - {name: upper_wall, shape: channel, axis: y, lower: 1.0, upper: 2.0}\n"          // 5
    "  - {name: cell, shape: disk, center: [0.6, 0.5], radius: 0.25}\n"                  // 6
    "particles:\n"                                                                       // 7
    "  spacing: 0.05\n"                                                                  // 8
    "  fill:\n"                                                                          // 9
    "    - {region: lower_wall, kind: wall}\n"                                           // 10
    "    - {region: upper_wall, kind: wall}\n"                                           // 11
    "    - {region: cell, kind: wall}\n"                                                 // 12
    "    - {kind: fluid}\n"                                                              // 13
    "fluid: {backend: sdpd, h_over_dx: 3.0, shear_viscosity: 0.1, gravity: [2.0, 0]}\n"  // 14
    "time: {coupling_step: 0.02, end: 0.1}\n";                                           // 15

double tait(double rho, double rho0, double c0) {
  return rho0 * c0 * c0 / 7.0 * (std::pow(rho / rho0, 7.0) - 1.0);
}

TEST(SceneFlowScales, AnObstacleSceneGetsASoundSpeedAndABackgroundPressure) {
  const Scene s = parse_scene(kObstacle, "scene.yaml");
  // 10 U with U = g H^2 / (8 nu) = 2 x 1^2 / 0.8 = 2.5 (H: 20 fluid rows + one spacing), above
  // sqrt(rho g L / 0.01) = sqrt(2 x 2 / 0.01) = 20.
  EXPECT_DOUBLE_EQ(s.fluid.sound_speed, 25.0);
  // p_b = the expected pressure variation rho g L = 4 at the fluid's density 1.
  EXPECT_LT(s.fluid.reference_density, 1.0);
  EXPECT_NEAR(tait(1.0, s.fluid.reference_density, 25.0), 4.0, 1e-9);
  ASSERT_EQ(s.chosen.size(), 2u);
  EXPECT_NE(s.chosen[0].find("sound speed c0 = 25"), std::string::npos) << s.chosen[0];
  EXPECT_NE(s.chosen[1].find("around (0.6, 0.5)"), std::string::npos) << s.chosen[1];
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
}

TEST(SceneFlowScales, AChannelWithoutABodyGetsNoBackgroundPressure) {
  const std::string text = replace_once(kObstacle, "    - {region: cell, kind: wall}\n", "");
  const Scene s = parse_scene(text, "scene.yaml");
  EXPECT_DOUBLE_EQ(s.fluid.sound_speed, 25.0);  // the Mach rule alone
  EXPECT_DOUBLE_EQ(s.fluid.reference_density, 1.0);
  EXPECT_EQ(s.chosen.size(), 1u);
}

TEST(SceneFlowScales, GivenValuesAreKeptAndLowOnesWarned) {
  const std::string text =
      replace_once(kObstacle, "shear_viscosity: 0.1,",
                   "shear_viscosity: 0.1, sound_speed: 8, reference_density: 1.0,");
  const Scene s = parse_scene(text, "scene.yaml");
  EXPECT_DOUBLE_EQ(s.fluid.sound_speed, 8.0);
  EXPECT_DOUBLE_EQ(s.fluid.reference_density, 1.0);
  EXPECT_TRUE(s.chosen.empty());
  ASSERT_EQ(s.warnings.size(), 2u);
  // c0 = 8 < sqrt(4 / 0.01) = 20; p_b = 0 < 4
  EXPECT_NE(s.warnings[0].find("14:"), std::string::npos) << s.warnings[0];
  bool speed = false, background = false;
  for (const auto& w : s.warnings) {
    speed = speed || w.find("c0 = 8 is below sqrt(dp / (0.01 rho)) = 20") != std::string::npos;
    background = background || w.find("background pressure 0 ") != std::string::npos;
  }
  EXPECT_TRUE(speed && background) << s.warnings[0] << "\n" << s.warnings[1];
  // the settings of docs/how-to-obstacle.md: no warning. Its particles keep density 1 (which
  // otherwise follows reference_density, leaving no background pressure: warned).
  const std::string howto = replace_once(kObstacle, "shear_viscosity: 0.1,",
                                         "shear_viscosity: 0.1, sound_speed: 20, "
                                         "reference_density: 0.98,");
  const Scene same = parse_scene(howto, "scene.yaml");
  ASSERT_EQ(same.warnings.size(), 1u);
  EXPECT_NE(same.warnings[0].find("fluid's density 0.98"), std::string::npos) << same.warnings[0];
  const Scene ok = parse_scene(
      replace_once(howto, "  spacing: 0.05\n", "  spacing: 0.05\n  density: 1.0\n"), "scene.yaml");
  EXPECT_TRUE(ok.warnings.empty()) << ok.warnings.front();
}

TEST(SceneFlowScales, AMovingLidSetsTheSpeed) {
  const std::string lid =
      "dimension: 2\n"
      "box: {lower: [-0.15, -0.15], upper: [1.15, 1.15]}\n"
      "regions:\n"
      "  - {name: lid, shape: box, lower: [-1, 1.0], upper: [2, 2]}\n"
      "  - {name: inside, shape: box, lower: [0, 0], upper: [1, 1]}\n"
      "particles:\n"
      "  spacing: 0.05\n"
      "  fill:\n"
      "    - {region: lid, kind: wall, velocity: [1.0, 0.0]}\n"
      "    - {region: inside, kind: fluid}\n"
      "    - {kind: wall}\n"
      "fluid: {backend: sdpd, h_over_dx: 3.0, shear_viscosity: 0.01}\n"
      "time: {coupling_step: 0.02, end: 0.1}\n";
  const Scene s = parse_scene(lid, "scene.yaml");
  EXPECT_DOUBLE_EQ(s.fluid.sound_speed, 10.0);  // 10 U, U = 1 (sqrt(rho U^2 / 0.01) = 10 too)
  ASSERT_EQ(s.chosen.size(), 1u);
  EXPECT_NE(s.chosen[0].find("the moving walls"), std::string::npos) << s.chosen[0];
}

TEST(SceneFlowScales, NothingToChooseFromIsRefusedAtTheFluidLine) {
  const std::string text = replace_once(kObstacle, ", gravity: [2.0, 0]", "");
  try {
    (void)parse_scene(text, "scene.yaml");
    FAIL() << "no error";
  } catch (const InvalidArgument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("scene.yaml:14:"), std::string::npos) << what;
    EXPECT_NE(what.find("fluid.sound_speed: missing, and nothing in the scene"), std::string::npos)
        << what;
  }
}

}  // namespace
}  // namespace sadr::orchestrator
