// SPDX-License-Identifier: MIT
// Deterministic inflow buffer end to end: examples/poiseuille_tracer_2d.yaml
// (SDPD, body-force-driven periodic channel) with a deterministic species D
// held at 3 in the inlet slab 0 <= x <= 0.1 by fluid_service. Checked in every
// output frame: every particle inside the slab holds exactly 3 (whatever moved
// in since the last step), the species spreads downstream of the slab by
// advection and diffusion, and the far end of the channel stays below the
// buffer value (the buffer is not a copy of itself everywhere).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "cli_test_support.hpp"

namespace sadr::e2e {
namespace {

TEST(InflowE2e, DeterministicBufferHoldsItsValueOnTheParticlesInsideInEveryFrame) {
  const fs::path d = scratch("inflow-deterministic");
  std::string text =
      read_file(fs::path(SADR_SOURCE_DIR) / "examples" / "poiseuille_tracer_2d.yaml");
  text = replace_once(text, "end: 10.0", "end: 2.0");
  text = replace_once(
      text, "  - {name: stripe,",
      "  - {name: inlet, shape: box, lower: [0.0, 0.0], upper: [0.1, 1.0]}\n  - {name: stripe,");
  text = replace_once(text, "time:\n",
                      "  - name: D\n    stochastic: false\n    diffusivity: 0.01\n"
                      "    boundaries:\n      - {region: inlet, condition: inflow, value: 3.0}\n"
                      "time:\n");
  const fs::path scene = write_scene(d, text);
  ASSERT_EQ(
      run(bin("sadr") + " run " + scene.string() + " -q --embedded -o " + (d / "out").string(),
          d / "run.log"),
      0)
      << read_file(d / "run.log");
  std::size_t checked = 0;
  double downstream = 0, far_max = 0;
  for (const auto& p : frames(d / "out")) {
    if (p.extension() != ".csv") continue;
    const CsvFrame f = read_csv(p);
    const auto& x = f.column("x");
    const auto& y = f.column("y");
    const auto& c = f.column("D");
    downstream = 0, far_max = 0;
    for (std::size_t i = 0; i < f.rows(); ++i) {
      const bool inside = x[i] >= 0.0 && x[i] <= 0.1 && y[i] >= 0.0 && y[i] <= 1.0;
      if (inside) {
        EXPECT_EQ(c[i], 3.0) << p << " particle " << i << " at x = " << x[i];
        ++checked;
      } else if (x[i] > 0.1 && x[i] < 0.3) {
        downstream += c[i];
      } else if (x[i] > 0.5 && x[i] < 0.6) {
        far_max = std::max(far_max, c[i]);
      }
    }
  }
  std::printf(
      "buffer particles checked: %zu; at t = 2: sum of D on 0.1 < x < 0.3 = %.3f, "
      "max on 0.5 < x < 0.6 = %.3g\n",
      checked, downstream, far_max);
  EXPECT_GT(checked, 100u);
  EXPECT_GT(downstream, 1.0);  // fed by the buffer (D starts at 0 everywhere)
  EXPECT_LT(far_max, 3.0);
  if (!HasFailure()) fs::remove_all(d);  // keep the evidence of a failure
}

}  // namespace
}  // namespace sadr::e2e
