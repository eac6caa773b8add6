// SPDX-License-Identifier: MIT
// The coupling loop under time.tolerance against deterministic in-process
// services (no noise, no processes): a "SSA" whose copy numbers decay as
// round(X0 exp(-lambda t)) and a "fluid" that integrates the copy numbers it
// is handed (the Boussinesq momentum of tests/e2e/splitting_test.cpp). The
// integral's error against the exact one is the splitting error alone, so it
// is checked against the tolerance exactly; rejected steps are restored from
// the snapshots; a stopped and resumed loop ends bit-identical.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "sadr/orchestrator/splitting_loop.hpp"

namespace sadr::orchestrator {
namespace {

constexpr double kLambda = 2.0;
const std::vector<double> kX0{1e5, 2e5, 4e5, 8e5};

std::string hex(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%a", v);
  return buf;
}

class IntegratingFluid final : public FluidService {
 public:
  FluidStep advance(std::uint64_t, double dt, bool, const SpeciesCounts& counts,
                    const std::vector<std::string>&) override {
    for (std::size_t i = 0; i < integral.size(); ++i) {
      integral[i] += dt * static_cast<double>(counts.values.at(0).at(i));
    }
    t += dt;
    ++advances;
    FluidStep r;
    r.time = t;
    r.substeps = 1;
    return r;
  }
  Geometry geometry() override { return {}; }
  FluidFrame frame(const std::vector<std::string>&) override { return {}; }
  std::string snapshot(std::uint64_t) override {  // t and the integrals, raw bytes
    std::vector<double> v{t};
    v.insert(v.end(), integral.begin(), integral.end());
    return {reinterpret_cast<const char*>(v.data()), v.size() * sizeof(double)};
  }
  void restore(const std::string& snap) override {
    ++restores;
    std::vector<double> v(snap.size() / sizeof(double));
    std::memcpy(v.data(), snap.data(), v.size() * sizeof(double));
    t = v.at(0);
    integral.assign(v.begin() + 1, v.end());
  }
  double t = 0.0;
  std::vector<double> integral = std::vector<double>(kX0.size(), 0.0);
  int advances = 0, restores = 0;
};

class DecayingSsa final : public SsaService {
 public:
  SsaStep advance(std::uint64_t, double t_end, Geometry, const std::vector<std::string>& names,
                  const SpeciesConcentrations&) override {
    const auto before = values(t);
    t = t_end;
    const auto after = values(t);
    SsaStep r;
    r.time = t_end;
    for (std::size_t i = 0; i < after.size(); ++i) {
      r.events += static_cast<std::uint64_t>(before[i] - after[i]);
    }
    r.counts = counts(names);
    return r;
  }
  SpeciesCounts counts(const std::vector<std::string>& names) override {
    SpeciesCounts c;
    for (const auto& n : names) {
      c.names.push_back(n);
      c.values.push_back(values(t));
    }
    return c;
  }
  std::string snapshot(std::uint64_t) override { return hex(t); }
  void restore(const std::string& s) override { t = std::stod(s); }
  static std::vector<std::int64_t> values(double t) {
    std::vector<std::int64_t> v;
    for (double x0 : kX0) v.push_back(std::llround(x0 * std::exp(-kLambda * t)));
    return v;
  }
  double t = 0.0;
};

LoopSettings controlled(Splitting splitting, double atol) {
  LoopSettings s;
  s.splitting = splitting;
  s.tau = 0.1;
  s.t_end = 1.0;
  s.output_times = {0.5, 1.0};
  s.fluid_calls_per_step = splitting == Splitting::kStrang ? 2 : 1;
  s.back_transfer = {"A"};
  StepTolerance tol;
  tol.absolute = atol;
  tol.max_step = 0.2;
  s.tolerance = tol;
  return s;
}

/// |integral the fluid saw - exact integral| / T, RMS over the particles.
double time_averaged_error(const IntegratingFluid& f) {
  double sum = 0.0;
  for (std::size_t i = 0; i < kX0.size(); ++i) {
    const double exact = kX0[i] * (1.0 - std::exp(-kLambda)) / kLambda;
    sum += (f.integral[i] - exact) * (f.integral[i] - exact);
  }
  return std::sqrt(sum / static_cast<double>(kX0.size()));
}

TEST(ControlledLoop, ErrorBelowTheToleranceAndRejectedStepsRestored) {
  for (const auto splitting : {Splitting::kLie, Splitting::kStrang}) {
    for (const double atol : {3000.0, 300.0, 30.0}) {
      IntegratingFluid fluid;
      DecayingSsa ssa;
      RunManifest stats;
      SplittingLoop loop(&fluid, &ssa, controlled(splitting, atol), stats);
      std::vector<double> frames;
      LoopHooks hooks;
      hooks.frame = [&](std::size_t, double t) { frames.push_back(t); };
      EXPECT_FALSE(loop.run(hooks));
      const auto& st = loop.controller()->stats();
      const double e = time_averaged_error(fluid);
      std::printf("%s atol %g: error %.2f (%.3f of atol), %llu accepted, %llu rejected\n",
                  splitting == Splitting::kLie ? "lie" : "strang", atol, e, e / atol,
                  static_cast<unsigned long long>(st.accepted),
                  static_cast<unsigned long long>(st.rejected));
      // At atol 30 the step the tolerance needs (about 6e-5 at the start) is below the
      // smallest step (1e-4): accepted there anyway, and counted. Otherwise the error is
      // below the tolerance (2 % for the rounding of the counts the estimate sees).
      if (atol >= 300) {
        EXPECT_EQ(st.over_tolerance, 0u);
        EXPECT_LT(e, atol * 1.02);
      } else {
        EXPECT_GT(st.over_tolerance, 0u);
        EXPECT_LE(st.smallest, loop.controller()->min_step() * (1 + 1e-9));
        // Strang here also meets the estimator's blind spot: the events (every decay)
        // bound a sampling noise these services do not have, and a second difference
        // below that bound reads as 0 (measured 1.15 atol).
        EXPECT_LT(e, atol * 1.25);
      }
      EXPECT_EQ(fluid.t, 1.0);  // time of the fluid: the accepted steps only
      EXPECT_EQ(loop.steps(), st.accepted);
      EXPECT_EQ(static_cast<std::uint64_t>(fluid.restores), st.rejected);
      EXPECT_EQ(frames, (std::vector<double>{0.5, 1.0}));  // frames only after accepted steps
      EXPECT_EQ(stats.step_control["accepted"], st.accepted);
    }
  }
}

TEST(ControlledLoop, StoppedAndResumedEndsBitIdentical) {
  for (const auto splitting : {Splitting::kLie, Splitting::kStrang}) {
    IntegratingFluid fluid;
    DecayingSsa ssa;
    RunManifest stats;
    SplittingLoop whole(&fluid, &ssa, controlled(splitting, 100.0), stats);
    whole.run({});
    // Stop after the first step past t = 0.3, save everything, resume in a new loop.
    IntegratingFluid f1;
    DecayingSsa s1;
    LoopSettings first = controlled(splitting, 100.0);
    first.stop_at = 0.3;
    SplittingLoop a(&f1, &s1, first, stats);
    EXPECT_TRUE(a.run({}));
    const std::string fs = f1.snapshot(0), ss = s1.snapshot(0), cs = a.control_state();
    IntegratingFluid f2;
    DecayingSsa s2;
    f2.restore(fs);
    s2.restore(ss);
    SplittingLoop b(&f2, &s2, controlled(splitting, 100.0), stats);
    b.resume_at(a.time(), a.steps());
    b.restore_control_state(cs);
    EXPECT_FALSE(b.run({}));
    EXPECT_EQ(b.steps(), whole.steps());
    EXPECT_EQ(b.controller()->state(), whole.controller()->state());
    for (std::size_t i = 0; i < kX0.size(); ++i) {
      EXPECT_EQ(hex(f2.integral[i]), hex(fluid.integral[i])) << i;
    }
    EXPECT_THROW(b.restore_control_state("{\"controller\": 1}"), std::exception);
  }
}

}  // namespace
}  // namespace sadr::orchestrator
