// SPDX-License-Identifier: MIT
// The plan's in-process backend init (the fluid sub-steps at t = 0) runs only when it fits the
// machine, and the plan says so when it does not.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "sadr/fluid/backend_schema.hpp"
#include "sadr/orchestrator/plan.hpp"
#include "sadr/orchestrator/scene_loader.hpp"
#include "sadr/orchestrator/work_estimate.hpp"

namespace sadr::orchestrator {
namespace {

TEST(WorkEstimate, InProcessInitCountsSadrPlusTheFluidShareOfOneRun) {
  WorkEstimate e;
  e.sadr_bytes = 10e6;
  e.fluid_bytes = 100e6;
  EXPECT_DOUBLE_EQ(in_process_init_bytes(e, 1), 10e6 + kInProcessInitFluidShare * 100e6);
  // -j 2: the estimate counts two runs at once, the init happens once, before them
  EXPECT_DOUBLE_EQ(in_process_init_bytes(e, 2), (10e6 + kInProcessInitFluidShare * 100e6) / 2);
}

TEST(WorkEstimate, InProcessInitFitsHalfTheMemoryAndTheProcessLimit) {
  MachineLimits m;
  m.memory_bytes = 1000e6;
  m.process_bytes = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(in_process_init_fits(500e6, m));
  EXPECT_FALSE(in_process_init_fits(500.1e6, m));
  m.process_bytes = 300e6;
  EXPECT_TRUE(in_process_init_fits(300e6, m));
  EXPECT_FALSE(in_process_init_fits(300.1e6, m));
}

TEST(WorkEstimate, APlanWithoutTheInitSaysWhyAndHowMuch) {
  WorkEstimate e;
  e.coupling_steps = 10;
  e.substeps_unknown = true;
  e.substeps_skipped = 3.0 * 1024 * 1024 * 1024;
  const std::string line = e.lines().at(1);
  EXPECT_NE(line.find("fluid sub-steps not computed"), std::string::npos) << line;
  EXPECT_NE(line.find("3 GiB"), std::string::npos) << line;
  e.substeps_skipped = 0;
  EXPECT_NE(e.lines().at(1).find("not known"), std::string::npos);
}

// A 2D sdpd channel of 20 x 10 particles, one tracer, 1 + 10 coupling steps: the wall time is
// the sum of its parts, each the count times its calibrated cost.
constexpr const char* kChannel = R"(name: channel
dimension: 2
box: {lower: [0.0, 0.0], upper: [2.0, 1.0], periodic: [true, true]}
particles: {spacing: 0.1}
fluid: {backend: sdpd, h_over_dx: 3.0, sound_speed: 10.0, shear_viscosity: 0.1}
species:
  - {name: T, diffusivity: 0.01, initial: [{count: 4}]}
time: {coupling_step: 0.1, end: 1.0}
output: {every: 0.5, formats: [csv]}
)";

TEST(WorkEstimate, WallTimeIsTheSumOfCountsTimesCalibratedCosts) {
  const Scene scene = parse_scene(kChannel, "channel.yaml");
  const Plan plan = make_plan(scene);
  MachineLimits m;
  m.memory_bytes = 1e12;
  m.process_bytes = std::numeric_limits<double>::infinity();
  m.free_disk_bytes = 1e15;
  FluidSubsteps fluid;
  fluid.stable_time_step = 0.01;
  fluid.limiting_criterion = "acoustic";
  fluid.max_substep = 0.01;
  const WorkEstimate e = estimate_work(scene, plan, m, 1, 1, &fluid);
  ASSERT_EQ(e.particles, 200.0);
  // 10 steps of 0.1 plus the 3 frames' split points; 0.1 / 0.01 = 10 sub-steps each; in all
  // end / dt plus half a sub-step of rounding per call
  EXPECT_DOUBLE_EQ(e.substeps_per_step, 10.0);
  const double calls = e.coupling_steps * plan.fluid_calls_per_step;
  EXPECT_DOUBLE_EQ(e.fluid_substeps, 1.0 / 0.01 + 0.5 * calls);
  const double fluid_s =
      200 * e.fluid_substeps * fluid::schema::find("sdpd")->cost.substep_ns[1] * 1e-9;
  const double graph_s = 200 * e.coupling_steps * kGraphRebuildNs[1] * 1e-9;
  const double ssa_s = e.events * kSsaEventNs * 1e-9;
  const double frames_s = e.frames * (kFrameSeconds + 200 * kFrameNsPerParticle * 1e-9);
  const double steps_s = e.coupling_steps * kStepSeconds;
  EXPECT_NEAR(e.wall_seconds, fluid_s + graph_s + ssa_s + frames_s + steps_s,
              1e-12 * e.wall_seconds);
  EXPECT_GT(ssa_s, 0.0);
  EXPECT_TRUE(e.notes.empty()) << "a run of well under an hour is not announced";
  EXPECT_NE(e.lines().back().find("of wall time on a 2-core machine (fluid"), std::string::npos)
      << e.lines().back();
  // 10 realizations, 2 at a time: five times the time of one
  const WorkEstimate ten = estimate_work(scene, plan, m, 10, 2, &fluid);
  EXPECT_NEAR(ten.wall_seconds, 5 * e.wall_seconds, 1e-9 * ten.wall_seconds);
  // A run of more than an hour is announced before it starts.
  fluid.max_substep = 1e-9;
  const WorkEstimate longer = estimate_work(scene, plan, m, 1, 1, &fluid);
  ASSERT_GT(longer.wall_seconds, kLongRunSeconds);
  ASSERT_EQ(longer.notes.size(), 1u);
  EXPECT_NE(longer.notes[0].find("this run will take about"), std::string::npos) << longer.notes[0];
  // Without the fluid's sub-steps there is no figure, and the plan says so.
  const WorkEstimate unknown = estimate_work(scene, plan, m, 1, 1, nullptr);
  EXPECT_EQ(unknown.wall_seconds, 0.0);
  EXPECT_NE(unknown.lines().back().find("wall time not estimated"), std::string::npos);
}

}  // namespace
}  // namespace sadr::orchestrator
