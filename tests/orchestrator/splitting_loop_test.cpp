// SPDX-License-Identifier: MIT
// The splitting loop against in-process fake services that log every call:
// Lie and Strang call order and step indices, steps shortened to land on
// output times, the geometry of each fluid stage handed to the next SSA
// stage, the back-transfer (counts from the SSA stage before, one fluid call),
// checkpoint cadence, stop_at, resume, and the overlap of SSA step k with
// fluid step k + 1.
#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <string>
#include <vector>

#include "sadr/orchestrator/splitting_loop.hpp"

namespace sadr::orchestrator {
namespace {

std::string fmt(const char* f, auto... args) {
  char buf[256];
  std::snprintf(buf, sizeof buf, f, args...);
  return buf;
}

/// The calls both fakes made, in order (thread-safe: the SSA may run on the worker).
struct CallLog {
  std::mutex mutex;
  std::condition_variable cv;
  std::vector<std::string> calls;
  void add(std::string call) {
    {
      std::lock_guard lock(mutex);
      calls.push_back(std::move(call));
    }
    cv.notify_all();
  }
  std::vector<std::string> of(char service) {
    std::lock_guard lock(mutex);
    std::vector<std::string> out;
    for (const auto& c : calls) {
      if (c[0] == service) out.push_back(c);
    }
    return out;
  }
};

std::string counts_text(const SpeciesCounts& c) {
  std::string s;
  for (std::size_t k = 0; k < c.names.size(); ++k) {
    s += " " + c.names[k] + "=" + std::to_string(c.values[k].at(0));
  }
  return s;
}

class FakeFluid final : public FluidService {
 public:
  explicit FakeFluid(CallLog& log, bool moves = true) : log_(log), moves_(moves) {}
  FluidStep advance(std::uint64_t step_index, double dt, bool want_geometry,
                    const SpeciesCounts& counts,
                    const std::vector<std::string>& return_concentrations) override {
    FluidStep r;
    t_ += dt;
    for (const auto& name : return_concentrations) r.concentrations.push_back({name, {t_}});
    r.time = t_;
    r.substeps = 2;
    r.particles_moved = moves_;
    if (want_geometry) r.geometry = Geometry::shared_memory(++generation_);
    log_.add(fmt("fluid %llu dt=%g geometry=%llu", static_cast<unsigned long long>(step_index), dt,
                 static_cast<unsigned long long>(r.geometry.generation())) +
             counts_text(counts));
    return r;
  }
  Geometry geometry() override {
    log_.add("fluid geometry");
    return Geometry::shared_memory(++generation_);
  }
  FluidFrame frame(const std::vector<std::string>&) override { return {}; }
  std::string snapshot(std::uint64_t) override { return "f"; }
  void restore(const std::string&) override {}

 private:
  CallLog& log_;
  bool moves_;
  double t_ = 0.0;
  std::uint64_t generation_ = 0;
};

class FakeSsa final : public SsaService {
 public:
  explicit FakeSsa(CallLog& log) : log_(log) {}
  SsaStep advance(std::uint64_t step_index, double t_end, Geometry geometry,
                  const std::vector<std::string>& return_counts,
                  const SpeciesConcentrations& frozen) override {
    if (before_advance) before_advance(step_index);
    std::string inputs;
    for (const auto& [name, values] : frozen) inputs += fmt(" %s=%g", name.c_str(), values.at(0));
    log_.add(fmt("ssa %llu t_end=%.17g geometry=%llu", static_cast<unsigned long long>(step_index),
                 t_end, static_cast<unsigned long long>(geometry.generation())) +
             inputs);
    SsaStep r;
    r.time = t_end;
    for (const auto& name : return_counts) {
      r.counts.names.push_back(name);
      r.counts.values.push_back({100 + static_cast<std::int64_t>(step_index)});
    }
    std::lock_guard lock(done_mutex_);
    done_ = step_index + 1;
    return r;
  }
  SpeciesCounts counts(const std::vector<std::string>& species) override {
    log_.add("ssa counts");
    SpeciesCounts c;
    for (const auto& name : species) {
      c.names.push_back(name);
      c.values.push_back({7});
    }
    return c;
  }
  std::string snapshot(std::uint64_t) override { return "s"; }
  void restore(const std::string&) override {}
  std::uint64_t steps_done() {
    std::lock_guard lock(done_mutex_);
    return done_;
  }
  std::function<void(std::uint64_t)> before_advance;

 private:
  CallLog& log_;
  std::mutex done_mutex_;
  std::uint64_t done_ = 0;
};

LoopSettings lie(double tau, double end) {
  LoopSettings s;
  s.tau = tau;
  s.t_end = end;
  s.fluid_calls_per_step = 1;
  s.geometry_each_step = true;
  return s;
}

TEST(SplittingLoop, LieRunsFluidThenSsaWithTheGeometryOfThatFluidStage) {
  CallLog log;
  FakeFluid fluid(log);
  FakeSsa ssa(log);
  RunManifest stats;
  SplittingLoop loop(&fluid, &ssa, lie(0.25, 0.5), stats);
  EXPECT_FALSE(loop.run({}));
  const std::vector<std::string> want = {
      "fluid 0 dt=0.25 geometry=1", "ssa 0 t_end=0.25 geometry=1", "fluid 1 dt=0.25 geometry=2",
      "ssa 1 t_end=0.5 geometry=2"};
  EXPECT_EQ(log.calls, want);
  EXPECT_EQ(loop.steps(), 2u);
  EXPECT_EQ(loop.time(), 0.5);
  EXPECT_EQ(stats.fluid_substeps, 4u);
}

TEST(SplittingLoop, StrangHalvesTheFluidAroundAFullSsaStage) {
  CallLog log;
  FakeFluid fluid(log);
  FakeSsa ssa(log);
  RunManifest stats;
  LoopSettings s = lie(0.5, 1.0);
  s.splitting = Splitting::kStrang;
  s.fluid_calls_per_step = 2;
  SplittingLoop loop(&fluid, &ssa, s, stats);
  loop.run({});
  // Only the half step before the SSA stage returns geometry; the fluid's call
  // indices run 2k, 2k + 1.
  const std::vector<std::string> want = {
      "fluid 0 dt=0.25 geometry=1", "ssa 0 t_end=0.5 geometry=1", "fluid 1 dt=0.25 geometry=0",
      "fluid 2 dt=0.25 geometry=2", "ssa 1 t_end=1 geometry=2",   "fluid 3 dt=0.25 geometry=0"};
  EXPECT_EQ(log.calls, want);
}

TEST(SplittingLoop, StepsAreShortenedToLandExactlyOnOutputTimes) {
  CallLog log;
  FakeFluid fluid(log, /*moves=*/false);
  FakeSsa ssa(log);
  RunManifest stats;
  LoopSettings s = lie(0.1, 0.35);
  s.output_times = {0.15, 0.35};
  SplittingLoop loop(&fluid, &ssa, s, stats);
  std::vector<std::string> frames;
  LoopHooks hooks;
  hooks.frame = [&](std::size_t index, double t) {
    // Both services are idle at a frame: the SSA stage of this step is done.
    frames.push_back(fmt("frame %zu t=%.17g after %llu ssa steps", index, t,
                         static_cast<unsigned long long>(ssa.steps_done())));
  };
  loop.run(hooks);
  // Particles did not move: no geometry goes to the SSA, the graph is kept.
  const std::vector<std::string> want_ssa = {
      "ssa 0 t_end=0.10000000000000001 geometry=0", "ssa 1 t_end=0.14999999999999999 geometry=0",
      "ssa 2 t_end=0.25 geometry=0", "ssa 3 t_end=0.34999999999999998 geometry=0"};
  EXPECT_EQ(log.of('s'), want_ssa);
  const std::vector<std::string> want_frames = {"frame 0 t=0.14999999999999999 after 2 ssa steps",
                                                "frame 1 t=0.34999999999999998 after 4 ssa steps"};
  EXPECT_EQ(frames, want_frames);
  EXPECT_EQ(loop.time(), 0.35);  // the output time itself, not an accumulated sum
}

TEST(SplittingLoop, BackTransferSendsTheLastSsaCountsWithEveryFluidStage) {
  CallLog log;
  FakeFluid fluid(log, /*moves=*/false);
  FakeSsa ssa(log);
  RunManifest stats;
  LoopSettings s = lie(0.5, 1.0);
  s.splitting = Splitting::kStrang;
  s.fluid_calls_per_step = 2;
  s.geometry_each_step = false;
  s.back_transfer = {"B"};
  s.overlap = true;  // ignored: the fluid reads the SSA
  SplittingLoop loop(&fluid, &ssa, s, stats);
  EXPECT_FALSE(loop.overlapping());
  loop.run({});
  // Copy numbers are read once (after Init); then each SSA stage returns them
  // and they ride on the next fluid calls: no separate round trip.
  const std::vector<std::string> want = {"ssa counts",
                                         "fluid 0 dt=0.25 geometry=0 B=7",
                                         "ssa 0 t_end=0.5 geometry=0",
                                         "fluid 1 dt=0.25 geometry=0 B=100",
                                         "fluid 2 dt=0.25 geometry=0 B=100",
                                         "ssa 1 t_end=1 geometry=0",
                                         "fluid 3 dt=0.25 geometry=0 B=101"};
  EXPECT_EQ(log.calls, want);

  // After a resume the restored SSA state is asked again.
  log.calls.clear();
  LoopSettings longer = s;
  longer.t_end = 1.5;
  SplittingLoop resumed(&fluid, &ssa, longer, stats);
  resumed.resume_at(1.0, 2);
  resumed.run({});
  ASSERT_GE(log.calls.size(), 2u);
  EXPECT_EQ(log.calls[0], "ssa counts");
  EXPECT_EQ(log.calls[1], "fluid 4 dt=0.25 geometry=0 B=7");
}

TEST(SplittingLoop, HybridFrozenConcentrationsGoFromTheFluidStageToTheNextSsaStage) {
  // Strang: only the half step just before an SSA stage returns them (the fake's
  // concentration is its clock, so each SSA stage shows which fluid stage fed it).
  CallLog log;
  FakeFluid fluid(log, /*moves=*/false);
  FakeSsa ssa(log);
  RunManifest stats;
  LoopSettings s = lie(0.5, 1.0);
  s.splitting = Splitting::kStrang;
  s.fluid_calls_per_step = 2;
  s.geometry_each_step = false;
  s.frozen = {"B"};
  SplittingLoop loop(&fluid, &ssa, s, stats);
  loop.run({});
  const std::vector<std::string> want = {"ssa 0 t_end=0.5 geometry=0 B=0.25",
                                         "ssa 1 t_end=1 geometry=0 B=0.75"};
  EXPECT_EQ(log.of('s'), want);
  // Lie: the SSA stage of step k holds the concentrations at the end of fluid stage k.
  log.calls.clear();
  FakeFluid lie_fluid(log, /*moves=*/false);
  LoopSettings l = lie(0.5, 1.0);
  l.frozen = {"B"};
  SplittingLoop lie_loop(&lie_fluid, &ssa, l, stats);
  lie_loop.run({});
  const std::vector<std::string> want_lie = {"ssa 0 t_end=0.5 geometry=0 B=0.5",
                                             "ssa 1 t_end=1 geometry=0 B=1"};
  EXPECT_EQ(log.of('s'), want_lie);
}

TEST(SplittingLoop, CheckpointsFollowTheCadenceAndStopAtStopsAfterOne) {
  CallLog log;
  FakeFluid fluid(log);
  FakeSsa ssa(log);
  RunManifest stats;
  LoopSettings s = lie(0.1, 0.5);
  s.checkpoint_every = 0.2;
  std::vector<double> at;
  SplittingLoop loop(&fluid, &ssa, s, stats);
  LoopHooks hooks;
  hooks.checkpoint = [&] { at.push_back(loop.time()); };
  EXPECT_FALSE(loop.run(hooks));
  ASSERT_EQ(at.size(), 3u);  // 0.2, 0.4 and the end
  EXPECT_NEAR(at[0], 0.2, 1e-15);
  EXPECT_NEAR(at[1], 0.4, 1e-15);
  EXPECT_EQ(at[2], 0.5);

  at.clear();
  s.stop_at = 0.3;
  SplittingLoop stopped(&fluid, &ssa, s, stats);
  hooks.checkpoint = [&] { at.push_back(stopped.time()); };
  EXPECT_TRUE(stopped.run(hooks));
  ASSERT_EQ(at.size(), 2u);  // 0.2, then 0.3 where it stopped
  EXPECT_NEAR(at[1], 0.3, 1e-15);
  EXPECT_EQ(stopped.steps(), 3u);
}

TEST(SplittingLoop, OverlapRunsSsaStepKWhileTheFluidComputesStepKPlus1) {
  CallLog log;
  FakeFluid fluid(log);
  FakeSsa ssa(log);
  RunManifest stats;
  LoopSettings s = lie(0.1, 0.4);
  s.overlap = true;
  // SSA step k waits (up to 20 s) for the fluid call of step k + 1: it can only
  // see it if the loop sent that call while SSA step k was still running.
  std::vector<bool> saw_next_fluid;
  ssa.before_advance = [&](std::uint64_t k) {
    const std::string next = fmt("fluid %llu ", static_cast<unsigned long long>(k + 1));
    std::unique_lock lock(log.mutex);
    const bool seen = log.cv.wait_for(lock, std::chrono::seconds(k + 1 < 4 ? 20 : 0), [&] {
      for (const auto& c : log.calls) {
        if (c.rfind(next, 0) == 0) return true;
      }
      return false;
    });
    saw_next_fluid.push_back(seen);
  };
  SplittingLoop loop(&fluid, &ssa, s, stats);
  EXPECT_TRUE(loop.overlapping());
  loop.run({});
  // Steps 0-2 overlapped; the last step (the end) runs its SSA stage alone.
  EXPECT_EQ(saw_next_fluid, (std::vector<bool>{true, true, true, false}));
  EXPECT_EQ(stats.overlapped_steps, 3u);
  // Each service still sees the same calls in the same order as without overlap.
  const auto fluid_calls = log.of('f');
  ASSERT_EQ(fluid_calls.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(fluid_calls[k].substr(0, 8), fmt("fluid %zu ", k));
    EXPECT_NE(fluid_calls[k].find(fmt("geometry=%zu", k + 1)), std::string::npos);
  }
  const auto ssa_calls = log.of('s');
  ASSERT_EQ(ssa_calls.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(ssa_calls[k].substr(0, 6), fmt("ssa %zu ", k));
    EXPECT_NE(ssa_calls[k].find(fmt("geometry=%zu", k + 1)), std::string::npos) << ssa_calls[k];
  }
}

}  // namespace
}  // namespace sadr::orchestrator
