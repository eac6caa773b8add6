// SPDX-License-Identifier: MIT
// The scene's Morris wall surfaces (fluid.wall_planes) reach ssa_service too when a stochastic
// species has a Dirichlet boundary, so its reservoirs hold their values on the same surfaces as
// the fluid's deterministic species (docs/ssa-core.md "Morris walls").
#include <gtest/gtest.h>

#include "sadr/orchestrator/plan.hpp"
#include "sadr/orchestrator/scene_loader.hpp"
#include "sadr/orchestrator/scene_messages.hpp"
#include "scene_test_support.hpp"

namespace sadr::orchestrator {
namespace {

const std::string kMorris = test::replace_once(
    test::kBaseScene, "  backend: static\n",
    "  backend: sdpd\n  sound_speed: 1\n  shear_viscosity: 0.1\n  wall_model: morris\n"
    "  wall_planes: [{region: left, point: [0.1], normal: [1]}]\n");

ssa::v1::SsaModel ssa_model(const std::string& text) {
  const Scene scene = parse_scene(text, "scene.yaml");
  return make_ssa_init(scene, make_plan(scene), 1, scene.particles).model();
}

TEST(SceneMessages, MorrisWallPlanesReachTheSsaWithADirichletSpecies) {
  const auto m = ssa_model(kMorris);
  ASSERT_EQ(m.wall_planes_size(), 1);
  EXPECT_EQ(m.wall_planes(0).region(), "left");
  EXPECT_EQ(m.wall_planes(0).point(0), 0.1);
  EXPECT_EQ(m.wall_planes(0).normal(0), 1.0);
  ASSERT_EQ(m.regions_size(), 1);
  EXPECT_EQ(m.regions(0).name(), "left");
}

TEST(SceneMessages, NoWallPlanesWithoutMorrisOrWithoutADirichletSpecies) {
  EXPECT_EQ(ssa_model(test::kBaseScene).wall_planes_size(), 0);
  const std::string no_flux = test::replace_once(
      kMorris, "    boundaries:\n      - {region: left, condition: dirichlet, value: 4}\n", "");
  EXPECT_EQ(ssa_model(no_flux).wall_planes_size(), 0);
}

}  // namespace
}  // namespace sadr::orchestrator
