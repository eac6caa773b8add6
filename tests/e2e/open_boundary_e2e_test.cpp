// SPDX-License-Identifier: MIT
// Open boundary end to end: examples/open_channel_tracer.yaml (SDPD open channel: parabolic
// inflow, outflow, recycling; a stochastic tracer held at 100 per particle in the inlet buffer
// by ssa_service) runs with the real services, in under a minute. Checked in every frame: the
// particle count and ids never change, the kinds include inlet and outlet particles and do
// change over the run (recycling), the particles inside the inlet buffer's box hold about 100
// molecules (reset at each SSA stage), and the tracer reaches the middle of the channel.
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
      "on 0.9 < x < 1.1 at the end = %.0f, run time %.1f s\n",
      frames_seen, n0, held, middle, seconds);
  EXPECT_EQ(frames_seen, 11u);
  EXPECT_TRUE(kinds_changed);
  EXPECT_GT(held, 500u);
  EXPECT_NEAR(held_sum / static_cast<double>(held), 100.0, 5.0);
  EXPECT_GT(middle, 1000.0);  // advected about half way down the channel by t = 10
  EXPECT_LT(seconds, 60.0);
  if (!HasFailure()) fs::remove_all(d);
}

}  // namespace
}  // namespace sadr::e2e
