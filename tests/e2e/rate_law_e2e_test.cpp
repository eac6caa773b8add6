// SPDX-License-Identifier: MIT
// Rate laws end to end (scene `parameters`, reaction `law`, `assigned` species),
// through the orchestrator and both services: static particles without diffusion,
// so every particle is a well-mixed reactor.
//  - deterministic Michaelis-Menten S -> P (catalyst E) against the exact solution;
//  - an expression law spelling the built-in one gives byte-identical frames, in
//    the deterministic and the stochastic path;
//  - an assigned species is written in every frame as its expression of the others.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "cli_test_support.hpp"

namespace sadr::e2e {
namespace {

std::string scene(const std::string& det_law, const std::string& sto_law) {
  return R"(name: laws
dimension: 1
box: {lower: [0.0], upper: [1.0], periodic: [true]}
particles: {spacing: 0.125}
fluid: {backend: static, h_over_dx: 2.0, max_time_step: 0.001}
parameters: {kcat: 0.8, Km: 0.5, Km_n: 20}
species:
  - {name: S, stochastic: false, diffusivity: 0, initial: [{concentration: 2.0}]}
  - {name: P, stochastic: false, diffusivity: 0}
  - {name: E, stochastic: false, diffusivity: 0, initial: [{concentration: 1.5}]}
  - {name: X, diffusivity: 0, initial: [{count: 60}]}
  - {name: Y, diffusivity: 0}
  - {name: F, diffusivity: 0, initial: [{count: 4}]}
  - {name: Q, assigned: "S*E/2 + X"}
reactions:
  - {name: det, equation: "S -> P", law: )" +
         det_law + R"(}
  - {name: sto, equation: "X -> Y", law: )" +
         sto_law + R"(}
time: {coupling_step: 0.25, end: 1.5}
output: {every: 0.5, formats: [csv]}
seed: 11
)";
}

const std::string kMm = "{type: michaelis_menten, kcat: kcat, Km: Km, catalyst: E}";
const std::string kMmExpr = "{type: expression, expression: \"kcat*E*S/(Km+S)\"}";
const std::string kStoMm = "{type: michaelis_menten, kcat: kcat, Km: Km_n, catalyst: F}";
const std::string kStoExpr = "{type: expression, expression: \"kcat*F*X/(Km_n+X)\"}";

fs::path run_scene(const std::string& name, const std::string& text) {
  const fs::path d = scratch("rate-law-" + name);
  const fs::path s = write_scene(d, text);
  EXPECT_EQ(run(bin("sadr") + " run " + s.string() + " -q --embedded -o " + (d / "out").string(),
                d / "run.log"),
            0)
      << read_file(d / "run.log");
  return d;
}

TEST(RateLawE2e, MichaelisMentenExactAndExpressionsIdenticalAndAssignedWritten) {
  const fs::path a = run_scene("builtin", scene(kMm, kStoMm));
  const fs::path b = run_scene("expression", scene(kMmExpr, kStoExpr));
  expect_same_frames(a / "out", b / "out");
  double worst = 0;
  std::size_t checked = 0;
  for (const auto& p : frames(a / "out")) {
    const CsvFrame f = read_csv(p);
    const auto& s = f.column("S");
    const auto& e = f.column("E");
    const auto& x = f.column("X");
    const auto& q = f.column("Q");
    for (std::size_t i = 0; i < f.rows(); ++i) {
      // X is a count in frames, a concentration X / V in Q (V = 0.125 here).
      EXPECT_DOUBLE_EQ(q[i], s[i] * e[i] / 2 + x[i] / 0.125) << p << " particle " << i;
      ++checked;
    }
    // The last frame (t = 1.5) against Km ln(S0/S) + S0 - S = kcat E t.
    if (p == frames(a / "out").back()) {
      double lo = 1e-9, hi = 2.0;
      auto g = [](double v) { return 0.5 * std::log(2.0 / v) + 2.0 - v - 0.8 * 1.5 * 1.5; };
      for (int k = 0; k < 200; ++k) {
        const double mid = 0.5 * (lo + hi);
        ((g(mid) > 0) == (g(lo) > 0) ? lo : hi) = mid;
      }
      for (std::size_t i = 0; i < f.rows(); ++i) worst = std::max(worst, std::fabs(s[i] - lo));
      EXPECT_LT(worst, 2e-7);
      for (std::size_t i = 0; i < f.rows(); ++i) EXPECT_LT(x[i], 60);  // X decays
    }
  }
  std::printf("MM deterministic |error| at t = 1.5: %.3g; assigned values checked: %zu\n", worst,
              checked);
  EXPECT_GT(checked, 0u);
  if (!HasFailure()) fs::remove_all(a), fs::remove_all(b);
}

}  // namespace
}  // namespace sadr::e2e
