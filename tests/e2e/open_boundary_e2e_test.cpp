// SPDX-License-Identifier: MIT
// Open boundary end to end: examples/open_channel_tracer.yaml (SDPD open channel: parabolic
// inflow, outflow, recycling; a stochastic tracer held at 100 per particle in the inlet buffer
// by ssa_service) runs with the real services, in under a minute. Checked in every frame: the
// particle count and ids never change, the kinds include inlet and outlet particles and do
// change over the run (recycling), the particles inside the inlet buffer's box hold about 100
// molecules (reset at each SSA stage), and the tracer reaches the middle of the channel.
// Also: a stochastic reaction on `fluid` only follows the kinds the fluid sends every step
// (shared memory and inline), so molecules in the buffers do not react.
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <vector>

#include "cli_test_support.hpp"

namespace sadr::e2e {
namespace {

TEST(OpenBoundaryE2e, OpenChannelTracerExampleRunsEndToEnd) {
  const fs::path d = scratch("open-boundary");
  const fs::path scene = fs::path(SADR_SOURCE_DIR) / "examples" / "open_channel_tracer.yaml";
  ASSERT_EQ(run(bin("sadr") + " validate " + scene.string(), d / "validate.log"), 0)
      << read_file(d / "validate.log");
  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_EQ(
      run(bin("sadr") + " run " + scene.string() + " -q -o " + (d / "out").string(), d / "run.log"),
      0)
      << read_file(d / "run.log");
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::size_t n0 = 0, frames_seen = 0, held = 0;
  double held_sum = 0;
  double middle = 0;
  std::vector<double> kinds0;
  bool kinds_changed = false;
  for (const auto& p : frames(d / "out")) {
    if (p.extension() != ".csv") continue;
    const CsvFrame f = read_csv(p);
    const auto& x = f.column("x");
    const auto& y = f.column("y");
    const auto& kind = f.column("kind");
    const auto& id = f.column("id");
    const auto& t = f.column("T");
    if (frames_seen++ == 0) {
      n0 = f.rows();
      kinds0 = kind;
    }
    ASSERT_EQ(f.rows(), n0) << p;
    std::size_t inlet = 0, outlet = 0;
    middle = 0;
    for (std::size_t i = 0; i < f.rows(); ++i) {
      EXPECT_EQ(id[i], static_cast<double>(i)) << p;
      inlet += kind[i] == 2.0;
      outlet += kind[i] == 3.0;
      if (x[i] >= -0.2 && x[i] <= -0.01 && y[i] >= 0.0 && y[i] <= 1.0) {
        // reset to 100 at the start of each SSA stage; frames come after the stage, in which
        // the buffer exchanges molecules with its neighbours (about kappa tau / dx^2 = 2%)
        EXPECT_GT(t[i], 70.0) << p << " particle " << i << " at x = " << x[i];
        EXPECT_LT(t[i], 130.0) << p << " particle " << i << " at x = " << x[i];
        held_sum += t[i];
        ++held;
      }
      if (x[i] > 0.9 && x[i] < 1.1) middle += t[i];
    }
    EXPECT_GT(inlet, 0u) << p;
    EXPECT_GT(outlet, 0u) << p;
    kinds_changed = kinds_changed || kind != kinds0;
  }
  std::printf(
      "open channel: %zu frames, %zu particles, %zu inlet-buffer values checked, tracer "
      "on 0.9 < x < 1.1 at the end = %.0f, run time %.1f s (printed, not asserted)\n",
      frames_seen, n0, held, middle, seconds);
  EXPECT_EQ(frames_seen, 11u);
  EXPECT_TRUE(kinds_changed);
  EXPECT_GT(held, 500u);
  EXPECT_NEAR(held_sum / static_cast<double>(held), 100.0, 5.0);
  EXPECT_GT(middle, 1000.0);  // advected about half way down the channel by t = 10
  if (!HasFailure()) fs::remove_all(d);
}

/// The example's channel with every non-wall particle filled as `fluid` (the fluid classifies
/// the buffers itself, so ssa_service starts with the scene's labels: all fluid), one
/// stochastic species at 50 per particle that does not diffuse (kappa = 0) and decays on fluid
/// particles only (the default kinds) at rate 20, up to t = 0.2.
std::string decay_scene(const fs::path& example) {
  std::string s = read_file(example);
  s = replace_once(s, "    - {region: inlet_buffer, kind: inlet, velocity: [0.1, 0.0]}\n", "");
  s = replace_once(s, "    - {region: outlet_buffer, kind: outlet}\n", "");
  const std::size_t a = s.find("species:\n"), b = s.find("time:\n");
  s = s.substr(0, a) +
      "species:\n  - {name: A, diffusivity: 0.0, initial: [{region: all, count: 50}]}\n"
      "reactions:\n  - {name: decay, equation: \"A -> 0\", rate: 20.0}\n"
      "time: {coupling_step: 0.05, end: 0.2}\n"
      "output: {times: [0.2], formats: [csv]}\nseed: 5\n";
  (void)b;
  return s;
}

TEST(OpenBoundaryE2e, AReactionOnFluidFollowsTheKindsTheFluidSendsEveryStep) {
  const fs::path d = scratch("open-boundary-kinds");
  const fs::path scene = write_scene(
      d, decay_scene(fs::path(SADR_SOURCE_DIR) / "examples" / "open_channel_tracer.yaml"));
  for (const std::string wire : {"shm", "inline", "embedded"}) {
    const fs::path out = d / wire;
    const std::string flags = wire == "inline"     ? " --no-shared-memory"
                              : wire == "embedded" ? " --embedded"
                                                   : "";
    ASSERT_EQ(run(bin("sadr") + " run " + scene.string() + " -q -o " + out.string() + flags,
                  d / (wire + ".log")),
              0)
        << read_file(d / (wire + ".log"));
    const auto fr = frames(out);
    ASSERT_FALSE(fr.empty());
    const CsvFrame f = read_csv(fr.back());
    const auto& x = f.column("x");
    const auto& kind = f.column("kind");
    const auto& a = f.column("A");
    // The inflow moves at most 0.15 * 0.2 = 0.03: particles now inlet with x < -0.05 were inlet
    // all along and must hold their 50 molecules exactly; particles in 0.3 < x < 1.7 were fluid
    // all along and keep each molecule with probability e^-4 = 0.018 (mean 0.9 of 50).
    std::size_t inlet = 0, fluid = 0;
    double fluid_sum = 0;
    for (std::size_t i = 0; i < f.rows(); ++i) {
      if (kind[i] == 2.0 && x[i] < -0.05) {
        ++inlet;
        EXPECT_EQ(a[i], 50.0) << wire << ": inlet particle " << i << " at x = " << x[i];
      } else if (kind[i] == 0.0 && x[i] > 0.3 && x[i] < 1.7) {
        ++fluid;
        fluid_sum += a[i];
      }
    }
    EXPECT_GT(inlet, 20u) << wire;
    EXPECT_GT(fluid, 300u) << wire;
    // The sum's mean is 0.92 N and its standard deviation 0.95 sqrt(N): 5 N is more than 70
    // standard deviations above the mean for N > 300 (false failure rate far below 1e-6);
    // without the decay it would be 50 N.
    EXPECT_LT(fluid_sum, 5.0 * static_cast<double>(fluid)) << wire;
  }
  expect_same_frames(d / "shm", d / "inline");
  expect_same_frames(d / "shm", d / "embedded");
  if (!HasFailure()) fs::remove_all(d);
}

}  // namespace
}  // namespace sadr::e2e
