// SPDX-License-Identifier: MIT
// Splitting stages and the alignment of coupling steps on output times.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "sadr/common/status.hpp"
#include "sadr/orchestrator/splitting.hpp"

namespace sadr::orchestrator {
namespace {

TEST(Splitting, LieIsFluidThenSsa) {
  const auto st = coupling_stages(Splitting::kLie, 1.0, 1.5);
  ASSERT_EQ(st.size(), 2U);
  EXPECT_EQ(st[0], (Stage{Operator::kFluid, 1.0, 1.5}));
  EXPECT_EQ(st[1], (Stage{Operator::kSsa, 1.0, 1.5}));
}

TEST(Splitting, StrangIsHalfFluidSsaHalfFluid) {
  const auto st = coupling_stages(Splitting::kStrang, 1.0, 1.5);
  ASSERT_EQ(st.size(), 3U);
  EXPECT_EQ(st[0], (Stage{Operator::kFluid, 1.0, 1.25}));
  EXPECT_EQ(st[1], (Stage{Operator::kSsa, 1.0, 1.5}));
  EXPECT_EQ(st[2], (Stage{Operator::kFluid, 1.25, 1.5}));
  EXPECT_DOUBLE_EQ(st[0].length() + st[2].length(), 0.5);
}

TEST(Splitting, SkippedOperatorsAreLeftOut) {
  auto st = coupling_stages(Splitting::kStrang, 0.0, 1.0, /*with_fluid=*/false, true);
  ASSERT_EQ(st.size(), 1U);
  EXPECT_EQ(st[0], (Stage{Operator::kSsa, 0.0, 1.0}));
  st = coupling_stages(Splitting::kStrang, 0.0, 1.0, true, /*with_ssa=*/false);
  ASSERT_EQ(st.size(), 1U);
  EXPECT_EQ(st[0], (Stage{Operator::kFluid, 0.0, 1.0}));
  EXPECT_TRUE(coupling_stages(Splitting::kLie, 0.0, 1.0, false, false).empty());
}

/// Runs the loop the orchestrator runs and returns the step ends.
std::vector<CouplingStep> run(double tau, double end, const std::vector<double>& outputs) {
  std::vector<CouplingStep> steps;
  double t = 0.0;
  while (auto s = next_coupling_step(t, tau, end, outputs)) {
    steps.push_back(*s);
    t = s->end;
    if (steps.size() > 10'000'000) break;
  }
  return steps;
}

TEST(Alignment, PlainStepsWhenNothingIsInTheWay) {
  const std::vector<double> out{0.0, 1.0};
  const auto s = next_coupling_step(0.0, 0.25, 1.0, out);
  ASSERT_TRUE(s);
  EXPECT_EQ(s->end, 0.25);
  EXPECT_FALSE(s->output);
  EXPECT_FALSE(s->last);
}

TEST(Alignment, ShortensToLandExactlyOnOutputTimes) {
  const std::vector<double> out{0.0, 0.3, 1.0};
  const auto s = next_coupling_step(0.25, 0.25, 1.0, out);
  ASSERT_TRUE(s);
  EXPECT_EQ(s->end, 0.3);  // bit-exact: the output time itself
  EXPECT_TRUE(s->output);
  EXPECT_DOUBLE_EQ(s->length(), 0.3 - 0.25);
}

TEST(Alignment, LastStepLandsOnEndTimeAndIsFlagged) {
  const std::vector<double> out{1.0};
  const auto steps = run(0.3, 1.0, out);
  ASSERT_EQ(steps.size(), 4U);
  EXPECT_EQ(steps.back().end, 1.0);
  EXPECT_TRUE(steps.back().last);
  EXPECT_TRUE(steps.back().output);
  EXPECT_NEAR(steps.back().length(), 0.1, 1e-12);
  EXPECT_FALSE(next_coupling_step(1.0, 0.3, 1.0, out));
  EXPECT_EQ(next_step_length(1.0, 0.3, 1.0, out), 0.0);
}

TEST(Alignment, RoundOffSliverIsMergedNotStepped) {
  // 0.1 added ten times is 0.9999999999999999: the naive loop would take an
  // 11th step of 1.1e-16. The aligned loop takes exactly ten.
  const std::vector<double> out{1.0};
  const auto steps = run(0.1, 1.0, out);
  ASSERT_EQ(steps.size(), 10U);
  EXPECT_EQ(steps.back().end, 1.0);
  for (const auto& s : steps) EXPECT_GT(s.length(), 0.1 * (1 - 1e-6));
}

TEST(Alignment, NoZeroOrTinyStepsOverManyOutputTimes) {
  // Output every 0.1 with tau = 0.1/3 and an awkward end: every step is either
  // tau or a landing step, and no step is shorter than 1e-9 tau.
  std::vector<double> out;
  for (int k = 0; k <= 100; ++k) out.push_back(0.1 * k);
  const double tau = 0.1 / 3.0;
  const auto steps = run(tau, 10.0, out);
  std::size_t frames = 0;
  for (const auto& s : steps) {
    EXPECT_GT(s.length(), 1e-9 * tau);
    EXPECT_LE(s.length(), tau * (1 + 1e-9));
    if (s.output) {
      ++frames;
      EXPECT_TRUE(std::binary_search(out.begin(), out.end(), s.end));
    }
  }
  EXPECT_EQ(frames, 100U);  // every output time after 0 is hit exactly once
  EXPECT_EQ(steps.back().end, 10.0);
}

TEST(Alignment, OutputTimeJustAfterAStepIsNotATinyStep) {
  // Target 1e-12 tau beyond t + tau: the step is stretched onto the target.
  const double tau = 0.01;
  const std::vector<double> out{tau + 1e-14, 1.0};
  const auto s = next_coupling_step(0.0, tau, 1.0, out);
  ASSERT_TRUE(s);
  EXPECT_EQ(s->end, tau + 1e-14);
  EXPECT_TRUE(s->output);
}

TEST(Alignment, OutputTimeWithinSnapOfCurrentTimeCountsAsReached) {
  const std::vector<double> out{0.5, 1.0};
  const auto s = next_coupling_step(0.5 - 1e-17, 0.1, 1.0, out);
  ASSERT_TRUE(s);
  EXPECT_NEAR(s->end, 0.6, 1e-15);
  EXPECT_FALSE(s->output);
}

TEST(Alignment, LargeTimesUseUlpScaledSnap) {
  // At t ~ 1e6 with tau = 1e-3, t + tau carries round-off of ~1e-10 = 1e-7 tau;
  // stepping 1000 times from 1e6 must still land on 1e6 + 1 exactly.
  const double start = 1e6;
  const std::vector<double> out{start + 1.0};
  double t = start;
  int n = 0;
  while (auto s = next_coupling_step(t, 1e-3, start + 1.0, out)) {
    t = s->end;
    ++n;
  }
  EXPECT_EQ(t, start + 1.0);
  EXPECT_EQ(n, 1000);
}

TEST(Alignment, EndTimeZeroTakesNoStep) {
  const std::vector<double> out{0.0};
  EXPECT_FALSE(next_coupling_step(0.0, 0.1, 0.0, out));
}

/// Records the operator calls a coupling loop makes, like a Stepper fake.
struct FakeStepper {
  std::vector<Stage> calls;
  double fluid_time = 0.0;  ///< each operator's own clock
  double ssa_time = 0.0;
  void apply(const Stage& s) {
    double& clock = s.op == Operator::kFluid ? fluid_time : ssa_time;
    EXPECT_EQ(s.begin, clock) << "operator " << to_string(s.op) << " skipped or repeated time";
    EXPECT_GT(s.length(), 0.0);
    clock = s.end;
    calls.push_back(s);
  }
};

TEST(Alignment, StagesTileTimeExactlyForBothSplittings) {
  const std::vector<double> out{0.0, 0.25, 0.5, 0.7, 1.0};
  for (const Splitting sp : {Splitting::kLie, Splitting::kStrang}) {
    FakeStepper fake;
    double t = 0.0;
    std::size_t steps = 0;
    while (auto step = next_coupling_step(t, 0.1, 1.0, out)) {
      for (const Stage& st : coupling_stages(sp, step->begin, step->end)) fake.apply(st);
      t = step->end;
      ++steps;
    }
    EXPECT_EQ(fake.fluid_time, 1.0);
    EXPECT_EQ(fake.ssa_time, 1.0);
    const std::size_t per_step = sp == Splitting::kStrang ? 3 : 2;
    EXPECT_EQ(fake.calls.size(), per_step * steps);
    // Order within a step: fluid first, and for Strang fluid again last.
    EXPECT_EQ(fake.calls[0].op, Operator::kFluid);
    EXPECT_EQ(fake.calls[1].op, Operator::kSsa);
    if (sp == Splitting::kStrang) {
      EXPECT_EQ(fake.calls[2].op, Operator::kFluid);
    }
  }
}

/// The loop of a frame-to-frame schedule (nothing moves): the step ends.
std::vector<double> frame_to_frame_ends(double tau, double end, const std::vector<double>& outputs,
                                        const FrameToFrame& ftf) {
  std::vector<double> ends;
  double t = 0.0;
  while (auto s = next_coupling_step(t, tau, end, outputs, &ftf)) {
    EXPECT_EQ(s->begin, t);
    EXPECT_GT(s->length(), 0.0);
    EXPECT_EQ(s->output, std::find(outputs.begin(), outputs.end(), s->end) != outputs.end());
    EXPECT_EQ(s->last, s->end == end);
    ends.push_back(s->end);
    t = s->end;
    if (ends.size() > 1000) break;
  }
  return ends;
}

TEST(FrameToFrame, OneStepPerOutputTimeWhateverTau) {
  const std::vector<double> out{0.0, 0.2, 0.4, 1.0, 4.0};
  // At most kFrameToFrameMaxSteps = 100 coupling steps (1.0 here) per step.
  EXPECT_EQ(frame_to_frame_ends(0.01, 4.0, out, {}),
            (std::vector<double>{0.2, 0.4, 1.0, 2.0, 3.0, 4.0}));
  EXPECT_EQ(frame_to_frame_ends(0.1, 4.0, out, {}), (std::vector<double>{0.2, 0.4, 1.0, 4.0}));
  // tau only sets the snap: an output 1e-12 after t counts as reached.
  EXPECT_EQ(frame_to_frame_ends(0.01, 1.0, {0.0, 1e-12, 0.5, 1.0}, {}),
            (std::vector<double>{0.5, 1.0}));
}

TEST(FrameToFrame, AlsoLandsOnCheckpointAndStopTimes) {
  const std::vector<double> out{0.0, 0.5, 2.0};
  FrameToFrame ftf;
  ftf.checkpoint_every = 0.3;
  ftf.stop_at = 1.0;
  const auto ends = frame_to_frame_ends(0.01, 2.0, out, ftf);
  // 0.3, 0.6, 0.9, 1.2 ... are multiples of 0.3 in floating point as the loop computes them.
  const std::vector<double> want{0.3, 0.5, 2 * 0.3, 3 * 0.3, 1.0, 4 * 0.3, 5 * 0.3, 6 * 0.3, 2.0};
  EXPECT_EQ(ends, want);
  // A checkpoint time within snap of an output time is that output time.
  ftf.checkpoint_every = 0.5 + 1e-13;
  ftf.stop_at = std::numeric_limits<double>::infinity();
  EXPECT_EQ(frame_to_frame_ends(0.01, 2.0, out, ftf),
            (std::vector<double>{0.5, 2 * ftf.checkpoint_every, 3 * ftf.checkpoint_every, 2.0}));
}

TEST(FrameToFrame, NullIsTheCouplingStepSchedule) {
  const std::vector<double> out{0.0, 0.25, 1.0};
  const auto a = next_coupling_step(0.0, 0.1, 1.0, out, nullptr);
  ASSERT_TRUE(a);
  EXPECT_EQ(a->end, 0.1);
  EXPECT_FALSE(next_coupling_step(1.0, 0.1, 1.0, out, nullptr));
  FrameToFrame ftf;
  EXPECT_THROW(next_coupling_step(0.0, 0.0, 1.0, out, &ftf), InvalidArgument);
}

TEST(Alignment, RejectsNonPositiveTau) {
  const std::vector<double> out{1.0};
  EXPECT_THROW(next_coupling_step(0.0, 0.0, 1.0, out), InvalidArgument);
  EXPECT_THROW(next_coupling_step(0.0, std::nan(""), 1.0, out), InvalidArgument);
}

}  // namespace
}  // namespace sadr::orchestrator
