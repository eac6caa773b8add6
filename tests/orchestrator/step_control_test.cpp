// SPDX-License-Identifier: MIT
// The error-controlled coupling step (docs/method.md section 1b): the
// splitting-error estimate of each hold rule on inputs with a known second
// derivative, the sampling noise kept out of it, the controller's accept /
// reject / grow / clamp decisions, and its state round-tripping exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "sadr/orchestrator/scene_loader.hpp"
#include "sadr/orchestrator/splitting.hpp"
#include "sadr/orchestrator/step_control.hpp"

namespace sadr::orchestrator {
namespace {

InputSample sample(double t, std::vector<double> v, double noise = 0.0) {
  InputSample s;
  s.time = t;
  s.value = std::move(v);
  s.noise = noise;
  return s;
}

StepTolerance absolute(double a) {
  StepTolerance t;
  t.absolute = a;
  t.max_step = 1.0;
  return t;
}

TEST(InputError, HeldAtOneEndIsHalfTheChange) {
  InputTrack track;
  track.rule = HoldRule::kEnd;
  EXPECT_FALSE(input_error(track, sample(0.1, {1.0, 2.0}), 0.1, absolute(1.0)));  // no sample
  accept_sample(track, sample(0.0, {10.0, 20.0}));
  // Changes 2 and -2: RMS 2, held value off by 1 on average over the step.
  const auto e = input_error(track, sample(0.1, {12.0, 18.0}), 0.1, absolute(0.5));
  ASSERT_TRUE(e);
  EXPECT_DOUBLE_EQ(*e, 2.0);
  StepTolerance rel;
  rel.relative = 0.01;  // scale 0.01 * max(RMS before, RMS after) = 0.01 * sqrt(250)
  EXPECT_NEAR(*input_error(track, sample(0.1, {12.0, 18.0}), 0.1, rel),
              1.0 / (0.01 * std::sqrt(250.0)), 1e-12);
}

TEST(InputError, TrapezoidAndMidpointUseTheSecondDerivative) {
  // y = t^2 (y'' = 2) sampled at 0, 0.1, 0.3: the trapezoid rule's error per unit
  // time over the last step (h = 0.2) is h^2/12 * 2, the midpoint rule's h^2/24 * 2.
  for (const auto rule : {HoldRule::kTrapezoid, HoldRule::kMidpoint}) {
    InputTrack track;
    track.rule = rule;
    accept_sample(track, sample(0.0, {0.0}));
    // One sample before: the first-order bound, half the change.
    EXPECT_DOUBLE_EQ(*input_error(track, sample(0.1, {0.01}), 0.1, absolute(1.0)), 0.005);
    accept_sample(track, sample(0.1, {0.01}));
    const auto e = input_error(track, sample(0.3, {0.09}), 0.2, absolute(1.0));
    ASSERT_TRUE(e);
    const double c = rule == HoldRule::kTrapezoid ? 1.0 / 12.0 : 1.0 / 24.0;
    EXPECT_NEAR(*e, c * 0.04 * 2.0, 1e-14);
  }
}

TEST(InputError, PoissonNoiseWithoutDriftIsNotSplittingError) {
  // 64 particles, copy numbers changed by pure noise: +-1 jumps, J_i ~ Poisson(mu) events
  // per particle (zero mean change), the noise bound 2 * events as the loop passes it.
  // 1000 independent steps at mu = 1, 10, 1000 (noise 10 to 1e4 times the tolerance):
  // the estimate must stay 0. False-failure rate: the sum of squares exceeds its bound
  // by 5 standard deviations (Gaussian 3e-7 per step); measured 0 of 3000 here.
  std::mt19937_64 rng(7);
  for (const double mu : {1.0, 10.0, 1000.0}) {
    int nonzero = 0;
    for (int trial = 0; trial < 1000; ++trial) {
      InputTrack track;
      track.counts = true;
      std::vector<double> before(64, 1e4), after(64);
      std::uint64_t events = 0;
      std::poisson_distribution<int> jumps(mu);
      std::bernoulli_distribution up(0.5);
      for (std::size_t i = 0; i < before.size(); ++i) {
        const int j = jumps(rng);
        events += static_cast<std::uint64_t>(j);
        int change = 0;
        for (int k = 0; k < j; ++k) change += up(rng) ? 1 : -1;
        after[i] = before[i] + change;
      }
      accept_sample(track, sample(0.0, before));
      const auto e = input_error(track, sample(0.1, after, 2.0 * static_cast<double>(events)), 0.1,
                                 absolute(0.001));
      ASSERT_TRUE(e);
      nonzero += *e > 0.0;
    }
    EXPECT_EQ(nonzero, 0) << "mu = " << mu;
  }
  // The same noise on top of a drift of 5 per particle: the drift is seen (not hidden).
  InputTrack track;
  track.counts = true;
  accept_sample(track, sample(0.0, std::vector<double>(64, 1e4)));
  std::vector<double> after(64);
  for (std::size_t i = 0; i < 64; ++i) after[i] = 1e4 + 100.0 + (i % 2 ? 3.0 : -3.0);
  const auto e = input_error(track, sample(0.1, after, 2.0 * 64 * 10), 0.1, absolute(1.0));
  ASSERT_TRUE(e);
  EXPECT_GT(*e, 45.0);  // 100 / 2 less what the noise bound removes
  EXPECT_LT(*e, 51.0);
}

TEST(StepController, RejectsShrinksGrowsAndClamps) {
  StepTolerance tol;
  tol.relative = 1e-3;
  tol.max_step = 0.4;
  StepController c(tol, 0.1, 1);
  EXPECT_DOUBLE_EQ(c.tau(), 0.1);
  EXPECT_DOUBLE_EQ(c.min_step(), 1e-4);
  EXPECT_FALSE(c.judge(0.1, 4.0));  // 4 x the tolerance: redo with 0.1 * 0.9 / 4
  EXPECT_NEAR(c.tau(), 0.0225, 1e-15);
  // An estimate of 0 after a rejection: capped at the rejection's step, the cap
  // growing by 1.25 per step.
  EXPECT_TRUE(c.judge(0.0225, 0.0));
  EXPECT_NEAR(c.tau(), 0.0225, 1e-15);
  EXPECT_TRUE(c.judge(0.0225, 0.0));
  EXPECT_NEAR(c.tau(), 0.0225 * 1.25, 1e-15);
  EXPECT_TRUE(c.judge(c.tau(), 0.9));  // at 0.9 of the tolerance: keep the step; cap gone
  EXPECT_NEAR(c.tau(), 0.0225 * 1.25, 1e-15);
  EXPECT_TRUE(c.judge(c.tau(), 0.0));  // no error: grow by at most 5
  EXPECT_NEAR(c.tau(), 0.0225 * 1.25 * 5, 1e-15);
  EXPECT_TRUE(c.judge(c.tau(), 0.0));
  EXPECT_DOUBLE_EQ(c.tau(), 0.4);    // clamped at max_step
  EXPECT_TRUE(c.judge(0.01, 0.01));  // a short landing step with room: tau kept
  EXPECT_DOUBLE_EQ(c.tau(), 0.4);
  EXPECT_TRUE(c.judge(0.4, std::nullopt));  // no estimate: accepted, tau kept
  EXPECT_FALSE(c.judge(0.4, 1e6));          // shrinks by at most 5
  EXPECT_DOUBLE_EQ(c.tau(), 0.08);
  // Order 2 (Strang): the error per unit time goes as tau^2.
  StepController s(tol, 0.1, 2);
  EXPECT_FALSE(s.judge(0.1, 4.0));
  EXPECT_NEAR(s.tau(), 0.1 * 0.9 / 2.0, 1e-15);
  const auto& st = c.stats();
  EXPECT_EQ(st.accepted, 7u);
  EXPECT_EQ(st.rejected, 2u);
  EXPECT_EQ(st.unestimated, 1u);
  EXPECT_DOUBLE_EQ(st.smallest, 0.01);
  EXPECT_DOUBLE_EQ(st.largest, 0.4);
  EXPECT_DOUBLE_EQ(st.largest_error, 0.9);
}

TEST(StepController, AcceptsAtTheSmallestStepAndCountsIt) {
  StepTolerance tol;
  tol.absolute = 1.0;
  tol.max_step = 1.0;
  StepController c(tol, 1.0, 1);
  double h = 1.0;
  int rejections = 0;
  while (!c.judge(h, 1e9)) {
    h = c.tau();
    ++rejections;
  }
  EXPECT_DOUBLE_EQ(h, 1e-3);
  EXPECT_EQ(rejections, 5);  // 1 -> 0.2 -> 0.04 -> 0.008 -> 0.0016 -> 0.001
  EXPECT_EQ(c.stats().over_tolerance, 1u);
}

TEST(StepController, AStepAtTheMinimumStretchedToLandIsStillAccepted) {
  // Two minimum steps before the end, a step may be stretched by up to 1e-9 of itself to land
  // on the end rather than leave a sliver (next_coupling_step): that step is still at the
  // minimum. Rejected, it would be redone at the same length forever (a run at
  // time.tolerance 1e-5 hung so).
  StepTolerance tol;
  tol.relative = 1e-5;
  tol.max_step = 0.1;
  StepController c(tol, 0.1, 1);
  const double end = 0.8, m = c.min_step();
  const double t = end - 2.0 * m * (1.0 + 5e-10);
  const auto cs = next_controlled_step(t, m, end, {});
  ASSERT_TRUE(cs);
  ASSERT_GT(cs->length(), m * (1.0 + 1e-12));  // the stretch this test is about
  EXPECT_TRUE(c.judge(cs->length(), 1e3));
  EXPECT_EQ(c.stats().over_tolerance, 1u);
  EXPECT_DOUBLE_EQ(c.tau(), m);
  EXPECT_FALSE(c.judge(2.0 * m, 1e3));  // above the minimum: still rejected
}

TEST(StepController, StateRoundTripsExactly) {
  StepTolerance tol;
  tol.relative = 1e-3;
  tol.max_step = 1.0;
  StepController a(tol, 0.1, 2);
  a.judge(0.1, 0.3);
  a.judge(a.tau() / 3.0, 1.7);
  StepController b(tol, 0.1, 2);
  b.set_state(nlohmann::json::parse(a.state().dump()));
  EXPECT_EQ(a.tau(), b.tau());
  EXPECT_EQ(a.state(), b.state());
  std::vector<InputTrack> tracks(1), back(1);
  tracks[0].name = back[0].name = "A";
  accept_sample(tracks[0], sample(0.1, {1.0 / 3.0, 7.0}));
  accept_sample(tracks[0], sample(0.1 + 1.0 / 7.0, {2.0 / 3.0, 9.0}, 12.0));
  tracks_from_json(nlohmann::json::parse(tracks_to_json(tracks).dump()), back);
  EXPECT_EQ(back[0].value, tracks[0].value);
  EXPECT_EQ(back[0].increment, tracks[0].increment);
  EXPECT_EQ(back[0].time, tracks[0].time);
  EXPECT_EQ(back[0].spacing, tracks[0].spacing);
  back[0].name = "B";
  EXPECT_THROW(tracks_from_json(tracks_to_json(tracks), back), std::exception);
  nlohmann::json bad = a.state();
  bad["tau"] = 5.0;  // beyond max_step
  EXPECT_THROW(b.set_state(bad), std::exception);
}

TEST(NextControlledStep, TwoHalvesInsteadOfASliver) {
  const std::vector<double> outputs{0.5, 1.0};
  auto length = [&](double t, double tau) {
    return next_controlled_step(t, tau, 1.0, outputs).value().length();
  };
  EXPECT_DOUBLE_EQ(length(0.0, 0.2), 0.2);    // the output 2.5 steps ahead: a plain step
  EXPECT_DOUBLE_EQ(length(0.0, 0.4), 0.25);   // 1.25 steps ahead: half the distance
  EXPECT_DOUBLE_EQ(length(0.25, 0.4), 0.25);  // then the landing
  EXPECT_TRUE(next_controlled_step(0.25, 0.4, 1.0, outputs)->output);
  EXPECT_DOUBLE_EQ(length(0.0, 0.6), 0.5);   // within one step: lands
  EXPECT_DOUBLE_EQ(length(0.5, 0.3), 0.25);  // the end 1.67 steps ahead
  EXPECT_FALSE(next_controlled_step(1.0, 0.3, 1.0, outputs));
}

Scene scene_with_time(const std::string& time) {
  return parse_scene(
      "dimension: 1\n"
      "box: {lower: [0.0], upper: [1.0], periodic: [true]}\n"
      "particles: {spacing: 0.125}\n"
      "fluid: {backend: static, h_over_dx: 2.0}\n"
      "species:\n  - {name: A, diffusivity: 0.1}\n"
      "time: " +
          time + "\n",
      "scene.yaml");
}

TEST(SceneTolerance, NumberMapAndAbsence) {
  EXPECT_FALSE(scene_with_time("{coupling_step: 0.1, end: 1.0}").time.tolerance);
  const auto a = scene_with_time("{coupling_step: 0.1, end: 1.0, tolerance: 1e-3}").time.tolerance;
  ASSERT_TRUE(a);
  EXPECT_EQ(a->relative, 1e-3);
  EXPECT_EQ(a->absolute, 0.0);
  EXPECT_EQ(a->max_step, 0.1);  // the first step
  const auto b =
      scene_with_time("{coupling_step: 0.1, end: 1.0, tolerance: {absolute: 5, max_step: 0.4}}")
          .time.tolerance;
  ASSERT_TRUE(b);
  EXPECT_EQ(b->relative, 0.0);
  EXPECT_EQ(b->absolute, 5.0);
  EXPECT_EQ(b->max_step, 0.4);
}

}  // namespace
}  // namespace sadr::orchestrator
