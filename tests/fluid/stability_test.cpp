// SPDX-License-Identifier: MIT
// Stability limits: a refused sub-step names the binding limit; a forced one that
// breaks it is said loudly (bench/validation/stability_map.py found forced runs at
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

TEST(Stability, RefusalNamesTheTightestLimitTheStepBreaks) {
  try {
    limits().check(1.0);  // breaks all three
    FAIL() << "not refused";
  } catch (const InvalidArgument& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("breaks the reaction stability limit 0.002"), std::string::npos) << m;
  }
  try {
    limits().check(0.01);  // breaks diffusion and reaction only
    FAIL() << "not refused";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("reaction"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(limits().check(0.002));
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
