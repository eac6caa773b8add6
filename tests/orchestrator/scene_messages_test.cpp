// SPDX-License-Identifier: MIT
// The scene's Morris wall surfaces (fluid.wall_planes) reach ssa_service too when a stochastic
// species has a Dirichlet boundary, so its reservoirs hold their values on the same surfaces as
// the fluid's deterministic species (docs/ssa-core.md "Morris walls"). The scene's meaning
// hash, and the fluid key (what the fluid receives and the coupling schedule).
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

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

std::string meaning(const std::string& text, const std::string& path = "scene.yaml") {
  const Scene scene = parse_scene(text, path);
  return scene_meaning_hash(scene, make_plan(scene));
}

TEST(SceneMessages, MeaningHashIsTheMeaningNotTheBytes) {
  const std::string base = meaning(test::kBaseScene);
  EXPECT_EQ(base.rfind("fnv1a64:", 0), 0u) << base;
  // Comments, flow vs block style, key order and the file's path do not change the meaning.
  std::string restyled =
      "# a comment\n" + test::replace_once(test::kBaseScene,
                                           "time:\n  coupling_step: 0.1\n  end: 1.0\n",
                                           "time: {end: 1.0, coupling_step: 0.1}\n");
  EXPECT_EQ(meaning(restyled, "elsewhere/scene.yaml"), base);  // the name comes from the file name
  // Every part of the meaning does.
  for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
           {"rate: 1.0", "rate: 1.5"},
           {"value: 4}", "value: 5}"},
           {"diffusivity: 0.2", "diffusivity: 0.3"},
           {"spacing: 0.25", "spacing: 0.125"},
           {"  end: 1.0\n", "  end: 2.0\n"},
           {"  backend: static\n", "  backend: static\n  reference_density: 2.0\n"}}) {
    EXPECT_NE(meaning(test::replace_once(test::kBaseScene, from, to)), base)
        << from << " -> " << to;
  }
  EXPECT_NE(meaning(test::kBaseScene + "seed: 3\n"), base);
}

/// kBaseScene (stochastic A, deterministic B on a static fluid) with a deterministic reaction.
const std::string kHybrid =
    test::replace_once(test::kBaseScene, "  - {equation: \"A -> 0\", rate: 1.0}\n",
                       "  - {equation: \"A -> 0\", rate: 1.0}\n"
                       "  - {equation: \"B -> 0\", rate: 0.5}\n");

std::string fluid_of(const std::string& text) {
  const Scene scene = parse_scene(text, "scene.yaml");
  const Plan plan = make_plan(scene);
  EXPECT_TRUE(plan.flow_replay_allowed) << plan.flow_replay_reason;
  return fluid_key(scene, plan);
}

// A sweep's points share a recorded flow exactly when their fluid keys are equal.
TEST(SceneMessages, FluidKeyIsWhatTheFluidReceivesAndWhenNotWhatOnlyTheSsaReceives) {
  const std::string base = fluid_of(kHybrid);
  EXPECT_EQ(base.rfind("fnv1a64:", 0), 0u) << base;
  EXPECT_NE(base, meaning(kHybrid));
  // What only the SSA receives (a stochastic reaction's rate, a stochastic species'
  // diffusivity and boundary value) and the seed: the same fluid.
  for (const auto& [from, to] :
       std::vector<std::pair<std::string, std::string>>{{"rate: 1.0", "rate: 1.5"},
                                                        {"value: 4}", "value: 5}"},
                                                        {"diffusivity: 0.1", "diffusivity: 0.4"}}) {
    const std::string text = test::replace_once(kHybrid, from, to);
    EXPECT_EQ(fluid_of(text), base) << from << " -> " << to;
    EXPECT_NE(meaning(text), meaning(kHybrid)) << from << " -> " << to;
  }
  EXPECT_EQ(fluid_of(kHybrid + "seed: 3\n"), base);
  // What the fluid receives (a deterministic reaction or species, a fluid parameter, the
  // particles), the coupling schedule and the output times: another fluid.
  for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
           {"rate: 0.5", "rate: 0.7"},
           {"diffusivity: 0.2", "diffusivity: 0.3"},
           {"  backend: static\n", "  backend: static\n  reference_density: 2.0\n"},
           {"spacing: 0.25", "spacing: 0.125"},
           {"  coupling_step: 0.1\n", "  coupling_step: 0.05\n"},
           {"  end: 1.0\n", "  end: 2.0\n"},
           {"  end: 1.0\n", "  end: 1.0\n  splitting: strang\n"},
           {"  end: 1.0\n", "  end: 1.0\noutput: {times: [0.5]}\n"}}) {
    EXPECT_NE(fluid_of(test::replace_once(kHybrid, from, to)), base) << from << " -> " << to;
  }
}

}  // namespace
}  // namespace sadr::orchestrator
