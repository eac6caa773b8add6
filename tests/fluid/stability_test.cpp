// SPDX-License-Identifier: MIT
// Stability limits: max_time_step only ever lowers the sub-step; a forced one that
// breaks the binding limit is said loudly (bench/validation/stability_map.py found forced runs at
// 1x the initial reaction limit that overshoot the Dirichlet value by 3.7 % silently).
#include <gtest/gtest.h>

#include <string>

#include "sadr/common/status.hpp"
#include "sadr/fluid/stability.hpp"

namespace sadr::fluid {
namespace {

StabilityLimits limits() {
  StabilityLimits l;
  l.acoustic = 0.02;
  l.diffusion = 0.004;
  l.reaction = 0.002;
  return l;
}

// max_time_step is an upper bound on the sub-step (docs/scene-format.md): above the binding limit
// the limit decides (the old rule refused it), below it max_time_step does; both rules.
TEST(Stability, MaxTimeStepIsAnUpperBoundNotARefusedOrForcedStep) {
  double stable = 1.0;
  std::string criterion;
  const Substep automatic = next_substep(limits(), 0.0, false, 0.01, stable, criterion);
  EXPECT_DOUBLE_EQ(automatic.dt, 0.01 / 5);  // ceil(0.01 / 0.002) pieces
  EXPECT_EQ(criterion, "reaction");
  for (const double above : {0.0021, 0.01, 1.0}) {
    const Substep s = next_substep(limits(), above, false, 0.01, stable, criterion);
    EXPECT_EQ(s.dt, automatic.dt) << above;
    EXPECT_EQ(s.limit_name, "reaction");
  }
  EXPECT_DOUBLE_EQ(next_substep(limits(), 0.0015, false, 0.01, stable, criterion).dt, 0.01 / 7);
  const UniformSubsteps u0 = uniform_substeps(limits(), 0.0, false, 0.01);
  EXPECT_EQ(u0.count, 5u);
  for (const double above : {0.0021, 0.01, 1.0}) {
    const UniformSubsteps u = uniform_substeps(limits(), above, false, 0.01);
    EXPECT_EQ(u.count, 5u) << above;
    EXPECT_EQ(u.dt, u0.dt) << above;
  }
  EXPECT_EQ(uniform_substeps(limits(), 0.0015, false, 0.01).count, 7u);
}

TEST(Stability, ForcedSubstepBeyondTheLimitWarnsOncePerLimit) {
  StabilityLimits l;
  l.viscous = 0.01;
  EXPECT_FALSE(warn_forced_substep(l, 0.005));  // within the limit: nothing to say
  testing::internal::CaptureStderr();
  EXPECT_TRUE(warn_forced_substep(l, 0.04));
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("force_time_step: sub-step 0.04 is 4x the viscous stability limit 0.01"),
            std::string::npos)
      << err;
  EXPECT_FALSE(warn_forced_substep(l, 0.04));  // once per limit
  // next_substep() with force takes the step, and warns through the same call.
  double stable = 1.0;
  std::string criterion;
  const Substep s = next_substep(l, 0.04, /*force=*/true, 0.08, stable, criterion);
  EXPECT_DOUBLE_EQ(s.dt, 0.04);
  EXPECT_EQ(criterion, "viscous");
}

}  // namespace
}  // namespace sadr::fluid
