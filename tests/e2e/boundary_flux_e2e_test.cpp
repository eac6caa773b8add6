// SPDX-License-Identifier: MIT
// Boundary fluxes (scene `boundary_fluxes`) end to end, on the static backend:
//  - well mixed (no diffusion): a constant influx and a Michaelis-Menten outflux of
//    deterministic species against dC/dt = +-(A_i / V_i) j(C), exactly; the amount added equals
//    A q t to round-off; the stochastic influx's total count against Poisson(A q t);
//  - a 1D slab with a constant Neumann flux q at x = 0 and diffusion against the semi-infinite
//    solution, at three resolutions (error and its order printed and bounded).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "cli_test_support.hpp"

namespace sadr::e2e {
namespace {

fs::path run_scene(const std::string& name, const std::string& text) {
  const fs::path d = scratch("flux-" + name);
  const fs::path s = write_scene(d, text);
  EXPECT_EQ(run(bin("sadr") + " run " + s.string() + " -q --embedded -o " + (d / "out").string(),
                d / "run.log"),
            0)
      << read_file(d / "run.log");
  return d;
}

// 2 x 1 box, x periodic, y walled, dx = 0.5: rows y = 0, 0.5, 1 of 4 particles (V = 0.25).
// Face y- (A = 2) is shared by the 4 particles of y = 0 (A_i = 0.5, A_i / V_i = 2), face y+ by
// those of y = 1.
const std::string kWellMixed = R"yaml(name: flux_mixed
dimension: 2
box: {lower: [0.0, 0.0], upper: [2.0, 1.0], periodic: [true, false]}
particles: {spacing: 0.5}
fluid: {backend: static, h_over_dx: 1.5, max_time_step: 0.001}
parameters: {q: 0.3, Vm: 0.8, Km: 0.5, qx: 400}
species:
  - {name: C, stochastic: false, diffusivity: 0, initial: [{concentration: 1.0}]}
  - {name: S, stochastic: false, diffusivity: 0, initial: [{concentration: 2.0}]}
  - {name: X, diffusivity: 0}
boundary_fluxes:
  - {name: influx, species: C, face: y-, law: {type: expression, expression: "q"}}
  - {name: uptake, equation: "S -> 0", face: y+, law: {type: expression, expression: "Vm*S/(Km+S)"}}
  - {name: birth, species: X, face: y-, law: {type: expression, expression: "qx"}}
time: {coupling_step: 0.25, end: 1.5}
output: {every: 0.5, formats: [csv]}
seed: 5
)yaml";

TEST(BoundaryFluxE2e, WellMixedFluxesMatchTheOdeAndConserveAndTheSsaIsPoisson) {
  const fs::path d = run_scene("mixed", kWellMixed);
  const auto fr = frames(d / "out");
  ASSERT_EQ(fr.size(), 4u);
  double worst_c = 0, worst_s = 0, worst_amount = 0;
  for (const auto& p : fr) {
    const CsvFrame f = read_csv(p);
    const double t = f.column("time")[0];
    const auto& y = f.column("y");
    const auto& c = f.column("C");
    const auto& s = f.column("S");
    const auto& x = f.column("X");
    // S(t) on y = 1: Km ln(S0 / S) + S0 - S = 2 Vm t (bisection).
    double lo = 1e-12, hi = 2.0;
    auto g = [t](double v) { return 0.5 * std::log(2.0 / v) + 2.0 - v - 2 * 0.8 * t; };
    for (int k = 0; k < 200; ++k) {
      const double mid = 0.5 * (lo + hi);
      ((g(mid) > 0) == (g(lo) > 0) ? lo : hi) = mid;
    }
    double added = 0, births = 0;
    for (std::size_t i = 0; i < f.rows(); ++i) {
      const bool bottom = y[i]<0.25, top = y[i]> 0.75;
      worst_c = std::max(worst_c, std::fabs(c[i] - (bottom ? 1.0 + 2 * 0.3 * t : 1.0)));
      worst_s = std::max(worst_s, std::fabs(s[i] - (top ? lo : 2.0)));
      added += (c[i] - 1.0) * 0.25;
      if (!bottom) {
        EXPECT_EQ(x[i], 0) << p << " particle " << i;
      }
      births += x[i];
    }
    // The amount added is A q t = 2 * 0.3 * t, to round-off.
    worst_amount = std::max(worst_amount, std::fabs(added - 2 * 0.3 * t));
    // Sum of the births: Poisson(A qx t) = Poisson(800 t); |z| <= 5 (false-failure rate 6e-7
    // per frame).
    if (t > 0) {
      const double mean = 2 * 400 * t;
      EXPECT_LE(std::fabs(births - mean) / std::sqrt(mean), 5.0) << p << " births " << births;
    } else {
      EXPECT_EQ(births, 0);
    }
  }
  std::printf("well mixed: |C - exact| %.3g, |S - exact| %.3g, |added - A q t| %.3g\n", worst_c,
              worst_s, worst_amount);
  EXPECT_LT(worst_c, 1e-12);  // a constant source is integrated exactly
  EXPECT_LT(worst_s, 1e-7);   // Heun's error at dt = 1e-3
  EXPECT_LT(worst_amount, 1e-12);
  if (!HasFailure()) fs::remove_all(d);
}

// Constant flux q into a semi-infinite medium x > 0 (Carslaw & Jaeger 2.9 (2)):
// C = (2 q / kappa) sqrt(kappa t / pi) exp(-x^2 / (4 kappa t)) - (q x / kappa) erfc(x / sqrt(4
// kappa t)). The slab [0, 1] with kappa t = 0.005 is semi-infinite to e^-50. The flux enters
// the first particle, at x = 0; the largest error sits in the kernel-truncated layer of width
// h = 2 dx next to the wall (measured: 9.5 %, 3.7 %, 1.8 % of the peak; order 1.4, 1.1).
double slab_error(int n, double* amount_error) {
  const double dx = 1.0 / n, kappa = 0.01, q = 0.5, t = 0.5;
  const std::string text = R"(name: flux_slab
dimension: 1
box: {lower: [0.0], upper: [1.0], periodic: [false]}
particles: {spacing: )" + std::to_string(dx) +
                           R"(}
fluid: {backend: static, h_over_dx: 2.0, parameters: {diffusion_eps: 0}}
species:
  - {name: C, stochastic: false, diffusivity: 0.01}
boundary_fluxes:
  - {species: C, face: x-, law: {type: expression, expression: "0.5"}}
time: {coupling_step: 0.5, end: 0.5}
output: {times: [0.5], formats: [csv]}
)";
  const fs::path d = run_scene("slab" + std::to_string(n), text);
  const CsvFrame f = read_csv(frames(d / "out").back());
  const auto& x = f.column("x");
  const auto& c = f.column("C");
  const double l = std::sqrt(4 * kappa * t);
  double err = 0, peak = 0, amount = 0;
  for (std::size_t i = 0; i < f.rows(); ++i) {
    const double s = x[i];
    const double exact =
        (2 * q / kappa) * std::sqrt(kappa * t / M_PI) * std::exp(-s * s / (l * l)) -
        (q * s / kappa) * std::erfc(s / l);
    err = std::max(err, std::fabs(c[i] - exact));
    peak = std::max(peak, exact);
    amount += c[i] * dx;
  }
  *amount_error = std::fabs(amount - q * t) / (q * t);
  fs::remove_all(d);
  return err / peak;
}

TEST(BoundaryFluxE2e, SlabWithAConstantFluxConvergesToTheSemiInfiniteSolution) {
  double amount[3];
  const double e1 = slab_error(50, &amount[0]);
  const double e2 = slab_error(100, &amount[1]);
  const double e3 = slab_error(200, &amount[2]);
  std::printf(
      "slab: max |C - exact| / max C at dx = 1/50, 1/100, 1/200: %.3g %.3g %.3g "
      "(orders %.2f %.2f); amount error %.2g %.2g %.2g\n",
      e1, e2, e3, std::log2(e1 / e2), std::log2(e2 / e3), amount[0], amount[1], amount[2]);
  for (double a : amount) EXPECT_LT(a, 1e-11);  // conservative: the total is q t to round-off
  EXPECT_GT(e1 / e3, 3.0);                      // at least order 0.8 (measured 1.2)
  EXPECT_LT(e3, 0.025);
}

// SDPD: a fluid at rest between wall particles (3 rows each side), a constant influx q on face
// y-: the amount in the fluid, sum C_i m_i / rho_i, grows by A q t (measured: to 2e-16; the
// densities stay at rest), and diffusion carries it up to the far row.
TEST(BoundaryFluxE2e, SdpdChannelAtRestReceivesAqt) {
  const std::string text = R"yaml(name: flux_sdpd
dimension: 2
box: {lower: [0.0, 0.0], upper: [2.0, 1.0], periodic: [true, false]}
regions:
  - {name: inside, shape: channel, axis: y, lower: 0.25, upper: 0.75}
particles:
  spacing: 0.1
  fill: [{region: inside, kind: fluid}, {kind: wall}]
fluid: {backend: sdpd, h_over_dx: 2.0, sound_speed: 10.0, shear_viscosity: 0.1}
species:
  - {name: C, stochastic: false, diffusivity: 0.01}
boundary_fluxes:
  - {species: C, face: y-, law: {type: expression, expression: "0.25"}}
time: {coupling_step: 0.1, end: 0.5}
output: {every: 0.5, formats: [csv]}
)yaml";
  const fs::path d = run_scene("sdpd", text);
  const CsvFrame f = read_csv(frames(d / "out").back());
  const auto& c = f.column("C");
  const auto& kind = f.column("kind");
  const auto& m = f.column("mass");
  const auto& rho = f.column("density");
  const auto& y = f.column("y");
  double amount = 0, top = 0;
  for (std::size_t i = 0; i < f.rows(); ++i) {
    if (kind[i] == 0) amount += c[i] * m[i] / rho[i];
    if (kind[i] != 0) {
      EXPECT_EQ(c[i], 0) << "wall particle " << i;
    }
    if (kind[i] == 0 && y[i] > 0.65) top += c[i];
  }
  const double expected = 2.0 * 0.25 * 0.5;
  std::printf("sdpd: amount %.9g against A q t = %.9g (relative %.2g)\n", amount, expected,
              std::fabs(amount - expected) / expected);
  EXPECT_LT(std::fabs(amount - expected) / expected, 1e-9);
  EXPECT_GT(top, 0);  // diffusion reached the far row (0.4 away, sqrt(kappa t) = 0.07): tiny
  if (!HasFailure()) fs::remove_all(d);
}

}  // namespace
}  // namespace sadr::e2e
