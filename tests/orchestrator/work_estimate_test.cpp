// SPDX-License-Identifier: MIT
// The plan's in-process backend init (the fluid sub-steps at t = 0) runs only when it fits the
// machine, and the plan says so when it does not.
#include <gtest/gtest.h>

#include <limits>
#include <string>

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

}  // namespace
}  // namespace sadr::orchestrator
