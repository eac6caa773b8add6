// SPDX-License-Identifier: MIT
// Scene `boundary_fluxes`: where the flux enters (the first fluid layer at the face, A_i shares
// summing to the face's area) and the refusals at load, each with file:line.
#include <gtest/gtest.h>

#include <numeric>
#include <string>

#include "sadr/common/status.hpp"
#include "sadr/orchestrator/scene_loader.hpp"
#include "scene_test_support.hpp"

namespace sadr::orchestrator {
namespace {

using test::replace_once;

// 2 x 1 box, x periodic, y walled, dx = 0.1: wall rows y = 0, 0.1, 0.2 and 0.8, 0.9, 1.0 (3
// rows each), fluid rows y = 0.3 .. 0.7 (5 rows of 20).
const std::string kScene =
    "dimension: 2\n"                                                                      // 1
    "box: {lower: [0, 0], upper: [2, 1], periodic: [true, false]}\n"                      // 2
    "regions:\n"                                                                          // 3
    "  - {name: walls, shape: channel, axis: y, lower: 0.25, upper: 0.75}\n"              // 4
    "  - {name: injury, shape: box, lower: [0.5, 0], upper: [1.0, 1]}\n"                  // 5
    "  - {name: ball, shape: disk, center: [1, 0.5], radius: 0.2}\n"                      // 6
    "particles:\n"                                                                        // 7
    "  spacing: 0.1\n"                                                                    // 8
    "  fill: [{region: walls, kind: fluid}, {kind: wall}]\n"                              // 9
    "fluid: {backend: static, h_over_dx: 1.5}\n"                                          // 10
    "parameters: {q: 2.0}\n"                                                              // 11
    "species:\n"                                                                          // 12
    "  - {name: A, stochastic: false, diffusivity: 0.1}\n"                                // 13
    "  - {name: B, diffusivity: 0.1}\n"                                                   // 14
    "boundary_fluxes:\n"                                                                  // 15
    "  - {name: in, species: A, face: y-, law: {type: expression, expression: \"q\"}}\n"  // 16
    "time: {coupling_step: 0.1, end: 1.0}\n";                                             // 17

std::string error_of(const std::string& text) {
  try {
    (void)parse_scene(text, "scene.yaml");
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "<no error>";
}

const std::string kLine16 =
    "  - {name: in, species: A, face: y-, law: {type: expression, expression: \"q\"}}\n";

TEST(BoundaryFluxScene, TheFirstFluidLayerSharesTheFaceAreaExactly) {
  const Scene s = parse_scene(kScene, "scene.yaml");
  ASSERT_EQ(s.reactions.size(), 1u);
  const Reaction& rx = s.reactions[0];
  EXPECT_FALSE(rx.stochastic);
  ASSERT_TRUE(rx.law.has_value());
  ASSERT_EQ(rx.boundary_particles.size(), 20u);  // the 20 fluid particles of y = 0.3
  for (const auto i : rx.boundary_particles) {
    EXPECT_EQ(s.particles.kind(i), ParticleKind::kFluid);
    EXPECT_NEAR(s.particles.positions[3 * i + 1], 0.3, 1e-12);
  }
  const double sum = std::accumulate(rx.boundary_areas.begin(), rx.boundary_areas.end(), 0.0);
  EXPECT_NEAR(sum, 2.0, 1e-12 * 2.0);  // A = the face's length
  for (const double a : rx.boundary_areas) EXPECT_NEAR(a, 0.1, 1e-12);
}

TEST(BoundaryFluxScene, APatchOfAFaceSharesItsArea) {
  const Scene p =
      parse_scene(replace_once(kScene, kLine16,
                               "  - {species: B, face: y+, region: injury, law: {type: expression, "
                               "expression: \"q*B\"}}\n"),
                  "scene.yaml");
  ASSERT_EQ(p.reactions.size(), 1u);
  const Reaction& rx = p.reactions[0];
  EXPECT_TRUE(rx.stochastic);
  EXPECT_EQ(rx.name, "flux0");
  ASSERT_EQ(rx.boundary_particles.size(), 5u);  // x = 0.55 .. 0.95 at y = 0.7
  for (const auto i : rx.boundary_particles) {
    EXPECT_NEAR(p.particles.positions[3 * i + 1], 0.7, 1e-12);
  }
  const double sum = std::accumulate(rx.boundary_areas.begin(), rx.boundary_areas.end(), 0.0);
  EXPECT_NEAR(sum, 0.5, 1e-12 * 0.5);
}

TEST(BoundaryFluxScene, WrongFluxesAreRefusedWithFileAndLine) {
  struct Case {
    std::string to;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {"  - {species: Z, face: y-, law: {type: expression, expression: \"q\"}}\n",
       "scene.yaml:16:15: boundary_fluxes[0].species: unknown species 'Z'"},
      {"  - {species: A, face: y-, law: {type: expression, expression: \"q*Y\"}}\n",
       "scene.yaml:16:33: boundary_fluxes[0].law: scene.yaml:16: rate law expression \"q*Y\": "
       "unknown symbol 'Y'"},
      {"  - {species: A, face: x-, law: {type: expression, expression: \"q\"}}\n",
       "face 'x-' is on a periodic axis"},
      {"  - {species: A, face: z-, law: {type: expression, expression: \"q\"}}\n",
       "face 'z-' is not a face of a 2D box"},
      {"  - {species: A, face: y-, region: ball, law: {type: expression, expression: \"q\"}}\n",
       "region 'ball' has shape"},
      {"  - {species: A, face: y-, law: {type: expression, expression: \"-q\"}}\n",
       "scene.yaml:16:33: boundary_fluxes[0].law: scene.yaml:16: rate law expression \"-q\": v = "
       "-2"},
      {"  - {species: A, face: y-}\n", "missing 'law'"},
      {"  - {species: A, equation: \"A -> 0\", face: y-, law: {type: expression, expression: "
       "\"q\"}}\n",
       "give either 'species'"},
  };
  for (const auto& c : cases) {
    const std::string msg = error_of(replace_once(kScene, kLine16, c.to));
    EXPECT_NE(msg.find(c.expected), std::string::npos) << c.to << "\n" << msg;
  }
  // No fluid particle on the patch: with x walled, the x- face's part 0 <= y <= 0.2 holds
  // wall particles only.
  const std::string walled = replace_once(
      replace_once(kScene, "periodic: [true, false]", "periodic: [false, false]"), kLine16,
      "  - {species: A, face: x-, region: low, law: {type: expression, "
      "expression: \"q\"}}\n");
  const std::string msg =
      error_of(replace_once(walled, "  - {name: ball,",
                            "  - {name: low, shape: box, lower: [0, 0], upper: [2, 0.2]}\n"
                            "  - {name: ball,"));
  EXPECT_NE(msg.find("no fluid particle lies on the face's part inside the region"),
            std::string::npos)
      << msg;
  // tdpd: deterministic fluxes refused by its capabilities; a stochastic one is fine.
  const std::string tdpd = replace_once(kScene, "fluid: {backend: static, h_over_dx: 1.5}",
                                        "fluid: {backend: tdpd, h_over_dx: 1.5}");
  const std::string t_msg = error_of(tdpd);
  EXPECT_NE(t_msg.find("scene.yaml:16:5: boundary_fluxes[0]: the 'tdpd' backend has no boundary "
                       "fluxes of deterministic species"),
            std::string::npos)
      << t_msg;
  EXPECT_EQ(error_of(replace_once(tdpd, kLine16,
                                  "  - {species: B, face: y-, law: {type: expression, "
                                  "expression: \"q\"}}\n")),
            "<no error>");
}

}  // namespace
}  // namespace sadr::orchestrator
