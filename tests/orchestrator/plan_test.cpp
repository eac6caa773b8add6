// SPDX-License-Identifier: MIT
// The plan: one test per skip rule, plus the text and JSON forms.
#include <gtest/gtest.h>

#include <algorithm>

#include "sadr/fluid/backend_schema.hpp"
#include "sadr/orchestrator/plan.hpp"

namespace sadr::orchestrator {
namespace {

Species species(const std::string& name, bool stochastic) {
  Species s;
  s.name = name;
  s.stochastic = stochastic;
  s.diffusivity = 0.1;
  return s;
}

Scene moving_scene() {
  Scene s;
  s.fluid.backend = "sdpd";
  s.fluid.temperature = 1.0;
  s.species = {species("A", true), species("C", false)};
  return s;
}

bool mentions(const std::vector<std::string>& lines, const std::string& text) {
  return std::any_of(lines.begin(), lines.end(),
                     [&](const std::string& l) { return l.find(text) != std::string::npos; });
}

TEST(Plan, FullHybridRunsEverything) {
  const Plan p = make_plan(moving_scene());
  EXPECT_TRUE(p.fluid_service);
  EXPECT_TRUE(p.fluid_stepping);
  EXPECT_TRUE(p.ssa_service);
  EXPECT_TRUE(p.graph_rebuild_each_step);
  EXPECT_TRUE(p.particles_to_ssa_each_step);
  EXPECT_TRUE(p.thermal_noise);
  EXPECT_FALSE(p.back_transfer);
  EXPECT_EQ(p.ssa_species, std::vector<std::string>{"A"});
  EXPECT_EQ(p.fluid_species, std::vector<std::string>{"C"});
  EXPECT_EQ(p.fluid_calls_per_step, 1);
}

TEST(Plan, ToleranceControlsTheStepOnlyWhenBothOperatorsRun) {
  Scene s = moving_scene();
  s.fluid.temperature = 0.0;
  s.time.coupling_step = 0.1;
  s.time.splitting = Splitting::kStrang;
  s.time.tolerance = StepTolerance{1e-3, 2.0, 0.5};
  Plan p = make_plan(s);
  EXPECT_TRUE(p.step_control);
  EXPECT_FALSE(p.overlap_allowed);  // a rejected step is redone by both services
  EXPECT_FALSE(p.flow_replay_allowed);
  EXPECT_TRUE(mentions(p.lines(),
                       "coupling step: error-controlled, tolerance relative 0.001, "
                       "absolute 2 (first step 0.1, at most 0.5, at least 0.0001; "
                       "splitting error of order 2"))
      << ::testing::PrintToString(p.lines());
  const auto j = p.to_json();
  EXPECT_EQ(j["step_control"]["order"], 2);
  EXPECT_EQ(j["step_control"]["max_step"], 0.5);
  EXPECT_FALSE(make_plan(moving_scene()).to_json().contains("step_control"));
  s.species = {species("A", true)};
  s.fluid.backend = "static";  // only the SSA runs: nothing to control
  p = make_plan(s);
  EXPECT_FALSE(p.step_control);
  EXPECT_TRUE(mentions(p.lines(), "skipped: error control (time.tolerance): not needed"));
}

TEST(Plan, NoSsaServiceWithoutStochasticSpecies) {
  Scene s = moving_scene();
  s.species = {species("C", false)};
  const Plan p = make_plan(s);
  EXPECT_FALSE(p.ssa_service);
  EXPECT_FALSE(p.graph_rebuild_each_step);
  EXPECT_TRUE(p.ssa_species.empty());
  EXPECT_TRUE(mentions(p.skipped, "ssa_service: not launched (no stochastic species)"));
}

TEST(Plan, StaticBackendDoesNotStepTheFluidAndBuildsTheGraphOnce) {
  Scene s = moving_scene();
  s.fluid.backend = "static";
  s.species = {species("A", true)};
  const Plan p = make_plan(s);
  EXPECT_FALSE(p.fluid_service);
  EXPECT_FALSE(p.fluid_stepping);
  EXPECT_TRUE(p.ssa_service);
  EXPECT_FALSE(p.graph_rebuild_each_step);
  EXPECT_FALSE(p.particles_to_ssa_each_step);
  EXPECT_FALSE(p.thermal_noise);  // even with k_B T > 0: nothing moves
  EXPECT_EQ(p.fluid_calls_per_step, 0);
  EXPECT_TRUE(mentions(p.skipped, "fluid_service: not launched"));
  EXPECT_TRUE(mentions(p.skipped, "built once"));
}

TEST(Plan, StaticBackendWithDeterministicSpeciesStillIntegratesThem) {
  Scene s = moving_scene();
  s.fluid.backend = "static";
  const Plan p = make_plan(s);
  EXPECT_TRUE(p.fluid_service);
  EXPECT_TRUE(p.fluid_stepping);
  EXPECT_FALSE(p.graph_rebuild_each_step);
  EXPECT_EQ(p.fluid_species, std::vector<std::string>{"C"});
  EXPECT_TRUE(mentions(p.skipped, "particle motion: none"));
}

// The plan reads what a backend does from its schema entry, for every backend there is.
TEST(Plan, DecidesFromTheBackendSchema) {
  for (const auto& b : sadr::fluid::schema::backends()) {
    Scene s = moving_scene();
    s.fluid.backend = b.name;
    s.species = {species("A", true)};  // no deterministic species
    const Plan p = make_plan(s);
    const bool moves = b.capabilities.moves_particles;
    EXPECT_EQ(p.graph_rebuild_each_step, moves) << b.name;
    EXPECT_EQ(p.fluid_service, moves) << b.name;
    EXPECT_EQ(p.thermal_noise, moves) << b.name;  // (k_B T = 1)
    EXPECT_EQ(mentions(p.skipped, "backend '" + b.name + "' moves no particles"), !moves) << b.name;
  }
}

TEST(Plan, NoNoiseAtZeroTemperature) {
  Scene s = moving_scene();
  s.fluid.temperature = 0.0;
  const Plan p = make_plan(s);
  EXPECT_FALSE(p.thermal_noise);
  EXPECT_TRUE(mentions(p.skipped, "thermal noise: none"));
}

TEST(Plan, BackTransferOnlyForBoussinesqFromStochasticSpecies) {
  Scene s = moving_scene();
  s.fluid.boussinesq = Boussinesq{"C", 1.0, 0.0, {0, 1, 0}};  // deterministic: no transfer
  Plan p = make_plan(s);
  EXPECT_FALSE(p.back_transfer);
  EXPECT_TRUE(mentions(p.skipped, "back-transfer ssa -> fluid: none"));
  s.fluid.boussinesq->species = "A";
  p = make_plan(s);
  EXPECT_TRUE(p.back_transfer);
  EXPECT_EQ(p.back_transfer_species, std::vector<std::string>{"A"});
  EXPECT_EQ(p.fluid_species, (std::vector<std::string>{"C", "A"}));  // A goes on the fluid wire
  EXPECT_EQ(p.ssa_species, std::vector<std::string>{"A"});
}

TEST(Plan, OnlyNeededSpeciesOnTheWire) {
  Scene s = moving_scene();
  s.species = {species("A", true), species("B", true), species("C", false), species("D", false)};
  const Plan p = make_plan(s);
  EXPECT_EQ(p.ssa_species, (std::vector<std::string>{"A", "B"}));
  EXPECT_EQ(p.fluid_species, (std::vector<std::string>{"C", "D"}));
}

TEST(Plan, StrangCallsTheFluidTwiceOnlyWithBothOperators) {
  Scene s = moving_scene();
  s.time.splitting = Splitting::kStrang;
  EXPECT_EQ(make_plan(s).fluid_calls_per_step, 2);
  s.species = {species("C", false)};
  const Plan p = make_plan(s);
  EXPECT_EQ(p.fluid_calls_per_step, 1);
  EXPECT_TRUE(mentions(p.skipped, "strang splitting: not needed"));
}

TEST(Plan, ReactionsAreCountedPerService) {
  Scene s = moving_scene();
  Reaction a;
  a.stochastic = true;
  Reaction c;
  c.stochastic = false;
  s.reactions = {a, a, c};
  const Plan p = make_plan(s);
  EXPECT_EQ(p.ssa_reactions, 2U);
  EXPECT_EQ(p.fluid_reactions, 1U);
}

TEST(Plan, StaticSsaOnlySceneSkipsTheCouplingStep) {
  Scene s = moving_scene();
  s.fluid.backend = "static";
  s.time.coupling_step = 0.01;
  s.species = {species("A", true)};
  Plan p = make_plan(s);
  EXPECT_TRUE(p.frame_to_frame);
  EXPECT_TRUE(mentions(p.lines(),
                       "skipped: coupling step (0.01): nothing moves; SSA advances "
                       "frame to frame"));
  EXPECT_EQ(p.to_json().at("frame_to_frame"), true);
  // An inflow buffer resets copy numbers at every SSA call: the step matters.
  s.species[0].boundaries.push_back({"inlet", BoundaryCondition::kInflow, 5.0});
  EXPECT_FALSE(make_plan(s).frame_to_frame);
  s.species[0].boundaries[0].condition = BoundaryCondition::kDirichlet;  // held inside the NSM
  EXPECT_TRUE(make_plan(s).frame_to_frame);
  // The fluid integrates a deterministic species every step, or particles move.
  s.species.push_back(species("C", false));
  EXPECT_FALSE(make_plan(s).frame_to_frame);
  EXPECT_FALSE(make_plan(moving_scene()).frame_to_frame);
}

TEST(Plan, TextAndJsonForms) {
  Scene s = moving_scene();
  s.fluid.temperature = 0.0;
  const Plan p = make_plan(s);
  const auto lines = p.lines();
  EXPECT_TRUE(mentions(
      lines, "fluid_service (" + s.fluid.backend + "): launched, advanced every coupling step"));
  EXPECT_TRUE(mentions(lines, "ssa_service: launched; species on the wire: A"));
  EXPECT_TRUE(mentions(lines, "thermal noise: off"));
  EXPECT_TRUE(mentions(lines, "skipped: thermal noise"));
  const auto j = p.to_json();
  EXPECT_EQ(j.at("ssa_service"), true);
  EXPECT_EQ(j.at("thermal_noise"), false);
  EXPECT_EQ(j.at("ssa_species"), nlohmann::json::array({"A"}));
  EXPECT_EQ(j.at("splitting"), "lie");
  EXPECT_EQ(j.at("fluid_backend"), s.fluid.backend);
  EXPECT_EQ(j.at("skipped").size(), p.skipped.size());
}

TEST(Plan, OverlapNeedsLieBothServicesNoBackTransferAndASpareCore) {
  Plan p = make_plan(moving_scene());
  ASSERT_TRUE(p.overlap_allowed);
  EXPECT_FALSE(p.overlap);  // off until decided
  decide_overlap(p, OverlapRequest::kAuto, 8, 7, 1);
  EXPECT_TRUE(p.overlap) << p.overlap_reason;
  EXPECT_NE(p.overlap_reason.find("auto: a second hardware thread"), std::string::npos)
      << p.overlap_reason;
  decide_overlap(p, OverlapRequest::kAuto, 2, 2, 1);  // the fluid's team uses both: still on
  EXPECT_TRUE(p.overlap) << p.overlap_reason;
  decide_overlap(p, OverlapRequest::kAuto, 1, 1, 1);
  EXPECT_FALSE(p.overlap);
  EXPECT_NE(p.overlap_reason.find("auto: no second hardware thread"), std::string::npos)
      << p.overlap_reason;
  decide_overlap(p, OverlapRequest::kAuto, 2, 1, 2);  // two realizations share the 2 cores
  EXPECT_FALSE(p.overlap);
  decide_overlap(p, OverlapRequest::kAuto, 8, 1, 4);
  EXPECT_TRUE(p.overlap);
  decide_overlap(p, OverlapRequest::kOn, 1, 1, 1);
  EXPECT_TRUE(p.overlap);
  EXPECT_EQ(p.overlap_reason, "--overlap");
  decide_overlap(p, OverlapRequest::kOff, 64, 1, 1);
  EXPECT_FALSE(p.overlap);
  EXPECT_EQ(p.overlap_reason, "--no-overlap");
  EXPECT_TRUE(mentions(p.lines(), "overlap ssa step k || fluid step k+1: off (--no-overlap)"));
  EXPECT_EQ(p.to_json().at("overlap"), false);
  EXPECT_EQ(p.to_json().at("overlap_reason"), "--no-overlap");

  Scene strang = moving_scene();
  strang.time.splitting = Splitting::kStrang;
  Plan ps = make_plan(strang);
  decide_overlap(ps, OverlapRequest::kOn, 64, 1, 1);
  EXPECT_FALSE(ps.overlap);  // even when asked for
  EXPECT_NE(ps.overlap_reason.find("strang"), std::string::npos) << ps.overlap_reason;

  Scene fed_back = moving_scene();
  fed_back.fluid.boussinesq = Boussinesq{"A", 1.0, 0.0, {0, 1, 0}};
  Plan pb = make_plan(fed_back);
  ASSERT_TRUE(pb.back_transfer);
  decide_overlap(pb, OverlapRequest::kOn, 64, 1, 1);
  EXPECT_FALSE(pb.overlap);
  EXPECT_NE(pb.overlap_reason.find("back-transfer"), std::string::npos) << pb.overlap_reason;

  Scene no_ssa = moving_scene();
  no_ssa.species.clear();
  Plan pn = make_plan(no_ssa);
  decide_overlap(pn, OverlapRequest::kOn, 64, 1, 1);
  EXPECT_FALSE(pn.overlap);
  EXPECT_EQ(pn.overlap_reason, "only one operator runs");
}

TEST(Plan, FlowReplayNeedsADeterministicFluidThatReadsNothingOfTheSsa) {
  Scene s = moving_scene();
  s.fluid.temperature = 0.0;
  Plan p = make_plan(s);
  ASSERT_TRUE(p.flow_replay_allowed) << p.flow_replay_reason;
  EXPECT_FALSE(p.flow_replay);  // off until decided
  decide_flow_replay(p, false, 20);
  EXPECT_TRUE(p.flow_replay);
  EXPECT_TRUE(mentions(p.lines(), "flow replay: on (the fluid is the same in every realization"));
  EXPECT_EQ(p.to_json().at("flow_replay"), true);
  decide_flow_replay(p, false, 1);
  EXPECT_FALSE(p.flow_replay);
  EXPECT_EQ(p.flow_replay_reason, "one realization");
  decide_flow_replay(p, true, 20);
  EXPECT_FALSE(p.flow_replay);
  EXPECT_TRUE(mentions(p.lines(), "flow replay: off (--no-flow-replay)"));
  EXPECT_EQ(p.to_json().at("flow_replay_reason"), "--no-flow-replay");

  // Each reason it must be refused, whatever is asked.
  auto refused = [](const Scene& scene, const std::string& why) {
    Plan q = make_plan(scene);
    EXPECT_FALSE(q.flow_replay_allowed) << why;
    decide_flow_replay(q, false, 20);
    EXPECT_FALSE(q.flow_replay) << why;
    EXPECT_NE(q.flow_replay_reason.find(why), std::string::npos) << q.flow_replay_reason;
  };
  refused(moving_scene(), "thermal noise on");  // k_B T = 1
  Scene fed_back = s;
  fed_back.fluid.boussinesq = Boussinesq{"A", 1.0, 0.0, {0, 1, 0}};
  refused(fed_back, "back-transfer ssa -> fluid: the fluid reads A");
  Scene hybrid = s;  // a deterministic reaction whose law reads the stochastic A
  Reaction rx;
  rx.name = "fed";
  rx.stochastic = false;
  rx.reads_other = {"A"};
  hybrid.reactions.push_back(rx);
  refused(hybrid, "back-transfer ssa -> fluid: the fluid reads A");
  Scene no_ssa = s;
  no_ssa.species = {species("C", false)};
  refused(no_ssa, "no stochastic species");
  Scene frozen = s;  // the SSA reads the fluid: allowed (the fluid's answers are replayed)
  Reaction sx;
  sx.name = "reads_c";
  sx.stochastic = true;
  sx.reads_other = {"C"};
  frozen.reactions.push_back(sx);
  EXPECT_TRUE(make_plan(frozen).flow_replay_allowed) << make_plan(frozen).flow_replay_reason;
}

}  // namespace
}  // namespace sadr::orchestrator
