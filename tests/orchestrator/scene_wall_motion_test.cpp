// SPDX-License-Identifier: MIT
// Moving walls in the scene (scene_wall_motion.cpp): a wall fill rule's velocity and a solid
// body's rigid `motion` become the wall particles' prescribed velocities; a motion with a
// component along the wall's surface normal and a backend that keeps walls at rest are refused
// at the key's line; with `moves: true` the body carries its motion (GeometryBody::moving), its
// walls start with the rigid-body velocity, the normal check does not apply, and the health check
// turns a turning body's tangent planes.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "sadr/common/status.hpp"
#include "sadr/orchestrator/run_health.hpp"
#include "sadr/orchestrator/scene_loader.hpp"
#include "scene_test_support.hpp"

namespace sadr::orchestrator {
namespace {

using test::replace_once;

std::string error_of(const std::string& text) {
  try {
    (void)parse_scene(text, "scene.yaml");
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "<no error>";
}

/// A 2D disk of radius 0.5 spinning at 2 about its centre (0, 0) inside a fixed container.
const std::string kSpinning =
    "dimension: 2\n"                                                                     // 1
    "box: {lower: [-1.3, -1.3], upper: [1.3, 1.3]}\n"                                    // 2
    "geometry:\n"                                                                        // 3
    "  spacing: 0.1\n"                                                                   // 4
    "  bodies:\n"                                                                        // 5
    "    - {name: gap, role: fluid, shape: {type: disk, center: [0, 0], radius: 1}}\n"   // 6
    "    - name: rotor\n"                                                                // 7
    "      role: solid\n"                                                                // 8
    "      shape: {type: disk, center: [0.0, 0.0], radius: 0.5}\n"                       // 9
    "      motion: {angular_velocity: 2.0, center: [0.0, 0.0]}\n"                        // 10
    "fluid: {backend: sdpd, h_over_dx: 3.0, sound_speed: 10.0, shear_viscosity: 0.1}\n"  // 11
    "time: {coupling_step: 0.1, end: 0.2}\n";                                            // 12

TEST(SceneWallMotion, ASpinningBodyGivesItsWallsOmegaCrossR) {
  const Scene s = parse_scene(kSpinning, "scene.yaml");
  const Region* rotor = s.find_region("rotor");
  ASSERT_NE(rotor, nullptr);
  ASSERT_FALSE(rotor->particles.empty());
  for (const auto i : rotor->particles) {
    const double x = s.particles.positions[3 * i], y = s.particles.positions[3 * i + 1];
    EXPECT_NEAR(s.particles.velocities[3 * i], -2.0 * y, 1e-12) << i;
    EXPECT_NEAR(s.particles.velocities[3 * i + 1], 2.0 * x, 1e-12) << i;
  }
  // the container's walls and the fluid stay at rest
  for (std::size_t i = 0; i < s.particles.size(); ++i) {
    if (std::hypot(s.particles.positions[3 * i], s.particles.positions[3 * i + 1]) < 0.5) continue;
    EXPECT_EQ(s.particles.velocities[3 * i], 0.0) << i;
  }
}

TEST(SceneWallMotion, SpinningAboutAnotherPointOrTranslatingIsRefusedAtTheMotion) {
  const std::string off =
      replace_once(kSpinning, "motion: {angular_velocity: 2.0, center: [0.0, 0.0]}",
                   "motion: {angular_velocity: 2.0, center: [0.1, 0.0]}");
  EXPECT_NE(error_of(off).find("scene.yaml:10:"), std::string::npos) << error_of(off);
  EXPECT_NE(error_of(off).find("along the surface normal"), std::string::npos);
  const std::string moving =
      replace_once(kSpinning, "motion: {angular_velocity: 2.0, center: [0.0, 0.0]}",
                   "motion: {velocity: [0.1, 0.0]}");
  EXPECT_NE(error_of(moving).find("along the surface normal"), std::string::npos);
  const std::string statics = replace_once(
      kSpinning, "backend: sdpd, h_over_dx: 3.0, sound_speed: 10.0, shear_viscosity: 0.1",
      "backend: static, h_over_dx: 3.0");
  EXPECT_NE(error_of(statics).find("keeps wall particles at rest"), std::string::npos)
      << error_of(statics);
}

TEST(SceneWallMotion, MovesMakesTheBodyTravelAndTurn) {
  const std::string text = replace_once(
      replace_once(kSpinning, "motion: {angular_velocity: 2.0, center: [0.0, 0.0]}",
                   "motion: {velocity: [0.1, -0.2], angular_velocity: 2.0, center: [0.1, 0.0], "
                   "moves: true}"),
      "shear_viscosity: 0.1}", "shear_viscosity: 0.1, wall_model: adami}");
  const Scene s = parse_scene(text, "scene.yaml");  // off-centre and translating: allowed
  ASSERT_TRUE(s.geometry);
  const GeometryBody* rotor = nullptr;
  for (const auto& b : s.geometry->bodies) {
    if (b.name == "rotor") {
      rotor = &b;
    } else {
      EXPECT_FALSE(b.moving) << b.name;
    }
  }
  ASSERT_NE(rotor, nullptr);
  ASSERT_TRUE(rotor->moving);
  EXPECT_EQ(rotor->moving->velocity[0], 0.1);
  EXPECT_EQ(rotor->moving->velocity[1], -0.2);
  EXPECT_EQ(rotor->moving->angular_velocity, 2.0);
  EXPECT_EQ(rotor->moving->center[0], 0.1);
  for (const auto i : s.find_region("rotor")->particles) {
    const double x = s.particles.positions[3 * i], y = s.particles.positions[3 * i + 1];
    EXPECT_NEAR(s.particles.velocities[3 * i], 0.1 - 2.0 * y, 1e-12) << i;
    EXPECT_NEAR(s.particles.velocities[3 * i + 1], -0.2 + 2.0 * (x - 0.1), 1e-12) << i;
  }
  const HealthContext c = health_context(s);
  ASSERT_EQ(c.turning.size(), 1u);
  ASSERT_EQ(c.tangent_turns.size(), c.tangents.size());
  std::size_t turned = 0;
  for (const int k : c.tangent_turns) turned += k == 0 ? 1 : 0;
  EXPECT_GT(turned, 0u);
  EXPECT_LT(turned, c.tangents.size());  // the container's walls stay
  // without `moves` (or with moves: false) the same motion is refused as before
  const std::string still = replace_once(text, "moves: true", "moves: false");
  EXPECT_NE(error_of(still).find("along the surface normal"), std::string::npos) << error_of(still);
  const std::string morris = replace_once(text, "wall_model: adami", "wall_model: morris");
  EXPECT_NE(error_of(morris).find("a moving body with fluid.wall_model morris that turns"),
            std::string::npos)
      << error_of(morris);
  const std::string translating =
      replace_once(morris, "angular_velocity: 2.0, center: [0.1, 0.0], ", "");
  EXPECT_EQ(error_of(translating), "<no error>");  // Morris on tangent planes that travel
}

/// Plane Couette: periodic x, walls below y = 0 (at rest) and above y = 1 (sliding at 0.5).
const std::string kCouette =
    "dimension: 2\n"                                                                     // 1
    "box: {lower: [0.0, -0.3], upper: [1.0, 1.3], periodic: [true, false]}\n"            // 2
    "regions:\n"                                                                         // 3
    "  - {name: bottom, shape: channel, axis: y, lower: -0.3, upper: -0.05}\n"           // 4
    "  - {name: top, shape: channel, axis: y, lower: 1.05, upper: 1.3}\n"                // 5
    "particles:\n"                                                                       // 6
    "  spacing: 0.1\n"                                                                   // 7
    "  fill:\n"                                                                          // 8
    "    - {region: bottom, kind: wall}\n"                                               // 9
    "    - {region: top, kind: wall, velocity: [0.5, 0.0]}\n"                            // 10
    "    - {kind: fluid}\n"                                                              // 11
    "fluid: {backend: sdpd, h_over_dx: 3.0, sound_speed: 10.0, shear_viscosity: 0.1}\n"  // 12
    "time: {coupling_step: 0.1, end: 0.2}\n";                                            // 13

TEST(SceneWallMotion, AWallFillRuleSlidesAlongItselfAndNotIntoTheFluid) {
  const Scene s = parse_scene(kCouette, "scene.yaml");
  int moving = 0;
  for (std::size_t i = 0; i < s.particles.size(); ++i) {
    const bool top = s.particles.positions[3 * i + 1] > 1.0;
    EXPECT_EQ(s.particles.velocities[3 * i], top ? 0.5 : 0.0) << i;
    moving += top ? 1 : 0;
  }
  EXPECT_GT(moving, 0);
  const std::string into = replace_once(kCouette, "velocity: [0.5, 0.0]", "velocity: [0.5, -0.1]");
  EXPECT_NE(error_of(into).find("scene.yaml:10:"), std::string::npos) << error_of(into);
  EXPECT_NE(error_of(into).find("normal to the wall"), std::string::npos);
}

}  // namespace
}  // namespace sadr::orchestrator
