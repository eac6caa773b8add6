// SPDX-License-Identifier: MIT
// A boundary flux on a curved surface (scene `boundary_fluxes` with `surface`), end to end on the
// static backend: a species released from the outline of a solid disk of radius R at a constant
// flux density j, decaying at rate k everywhere and diffusing with D, in a closed box.
//
// Steady state (2D): D (c'' + c' / r) = k c for r > R, -D c'(R) = j, c -> 0: with
// lambda = sqrt(D / k),
//     c(r) = j lambda K0(r / lambda) / (D K1(R / lambda)).
// (3D, for a sphere: c(r) = j R^2 exp(-(r - R) / lambda) / (D r (1 + R / lambda)).)
// The box [-4, 4]^2 with R = lambda = 0.5 is infinite to K0(8) / K0(1) = 3.5e-4. No
// regularisation of the Laplacian (diffusion_eps and the SSA's regularization 0): it would
// shift the profile by O(eps).
//
// Checked:
//  - the amount: with uniform decay, the total obeys dN/dt = j A - k N whatever the diffusion,
//    N(t) = j A (1 - e^{-kt}) / k with A = 2 pi R: the deterministic amount to 1e-6 (the time
//    integration), the stochastic total over R realizations against Poisson (N(t) is Poisson
//    exactly for births and independent deaths from zero);
//  - the stochastic mean on the particle graph: from zero, X_i(t) is Poisson(lambda_i(t)), and
//    lambda_i = V_i C_i (j_X / j_C) with C the deterministic species on the same graph (the
//    static backend's species Laplacian is the SSA graph's, docs/method.md). Per radial bin,
//    the count summed over the realizations against Poisson, Bonferroni over the bins with a
//    family-wise false-failure rate of 1e-3;
//  - the deterministic profile against c(r) (printed, bounded: it carries the SPH error next
//    to the wall particles).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "cli_test_support.hpp"

namespace sadr::e2e {
namespace {

constexpr double kR = 0.5, kD = 0.25, kK = 1.0, kJc = 1.0, kJx = 1000.0, kT = 8.0;
constexpr int kRealizations = 4;

/// The disk scene at spacing dx; with `stochastic` also the stochastic species X (j = 1000).
std::string disk_scene(double dx, bool stochastic) {
  std::string text = R"yaml(name: surface_flux_disk
dimension: 2
box: {lower: [-4.0, -4.0], upper: [4.0, 4.0]}
geometry:
  spacing: )yaml";
  char spacing[32];
  std::snprintf(spacing, sizeof spacing, "%.12g", dx);
  text += spacing;
  text += R"yaml(
  bodies:
    - {name: cell, role: solid, shape: {type: disk, center: [0.0, 0.0], radius: 0.5}}
fluid: {backend: static, h_over_dx: 2.0, parameters: {diffusion_eps: 0}}
ssa: {regularization: 0}
species:
  - {name: C, stochastic: false, diffusivity: 0.25}
reactions:
  - {name: decay_c, equation: "C -> 0", rate: 1.0}
boundary_fluxes:
  - {name: release_c, species: C, surface: cell, law: {type: expression, expression: "1"}}
time: {coupling_step: 0.5, end: 8.0}
output: {times: [8.0], formats: [csv]}
seed: 3
)yaml";
  if (stochastic) {
    text = replace_once(text, "reactions:\n",
                        "  - {name: X, diffusivity: 0.25}\nreactions:\n  - {name: decay_x, "
                        "equation: \"X -> 0\", rate: 1.0}\n");
    text = replace_once(text, "time:",
                        "  - {name: release_x, species: X, surface: cell, law: {type: expression, "
                        "expression: \"1000\"}}\ntime:");
  }
  return text;
}

double exact_profile(double r) {
  const double lam = std::sqrt(kD / kK);
  return kJc * lam * std::cyl_bessel_k(0.0, r / lam) / (kD * std::cyl_bessel_k(1.0, kR / lam));
}

struct Profile {
  double max_rel = 0, rms_rel = 0;  ///< |C - c(r)| / c(R) over the fluid
  double amount_rel = 0;            ///< |sum C V - N(t)| / N(t)
};

/// The deterministic species of one frame against c(r) and the amount N(t).
Profile deterministic_errors(const CsvFrame& f) {
  const auto& x = f.column("x");
  const auto& y = f.column("y");
  const auto& kind = f.column("kind");
  const auto& c = f.column("C");
  const auto& m = f.column("mass");
  const auto& rho = f.column("density");
  const double c0 = exact_profile(kR);
  Profile p;
  double amount = 0, sum2 = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < f.rows(); ++i) {
    if (kind[i] != 0) continue;
    const double e = std::fabs(c[i] - exact_profile(std::hypot(x[i], y[i]))) / c0;
    p.max_rel = std::max(p.max_rel, e);
    sum2 += e * e;
    ++n;
    amount += c[i] * m[i] / rho[i];
  }
  p.rms_rel = std::sqrt(sum2 / static_cast<double>(n));
  const double total = kJc * 2 * std::numbers::pi * kR * (1 - std::exp(-kK * kT)) / kK;
  p.amount_rel = std::fabs(amount - total) / total;
  return p;
}

fs::path run_disk(const std::string& name, double dx, int realizations) {
  const fs::path d = scratch("surface-flux-" + name);
  const fs::path s = write_scene(d, disk_scene(dx, realizations > 1));
  std::string cmd =
      bin("sadr") + " run " + s.string() + " -q --embedded -o " + (d / "out").string();
  if (realizations > 1) cmd += " -r " + std::to_string(realizations) + " -j 1";
  EXPECT_EQ(run(cmd, d / "run.log"), 0) << read_file(d / "run.log");
  return d;
}

#ifndef SADR_SURFACE_FLUX_VALIDATION
TEST(SurfaceFluxE2e, DiskReleasesJATimesTheAreaAndTheSsaMeanIsTheGraphsSteadyState) {
  const fs::path d = run_disk("fast", 0.1, kRealizations);
  std::vector<CsvFrame> fr;
  for (int r = 0; r < kRealizations; ++r) {
    char sub[32];
    std::snprintf(sub, sizeof sub, "realization_%04d", r);
    const auto files = frames(d / "out" / sub);
    ASSERT_EQ(files.size(), 2u) << sub;  // t = 0 and t = 8
    fr.push_back(read_csv(files.back()));
  }
  const CsvFrame& f0 = fr[0];
  ASSERT_NEAR(f0.column("time")[0], kT, 1e-12);
  // Deterministic: amount and profile (the same in every realization).
  const Profile p = deterministic_errors(f0);
  std::printf("disk dx = 0.1: amount error %.2g; |C - c(r)| / c(R): max %.3g, RMS %.3g\n",
              p.amount_rel, p.max_rel, p.rms_rel);
  EXPECT_LT(p.amount_rel, 1e-6);
  EXPECT_LT(p.max_rel, 0.08);   // measured 0.056, in the first layer
  EXPECT_LT(p.rms_rel, 0.005);  // measured 0.0031
  // Stochastic: the total over the realizations, and per radial bin of width 0.25.
  const auto& x = f0.column("x");
  const auto& y = f0.column("y");
  const auto& kind = f0.column("kind");
  const auto& c = f0.column("C");
  const auto& m = f0.column("mass");
  const auto& rho = f0.column("density");
  constexpr int kBins = 10;  // r in [R, R + 2.5)
  std::vector<double> expected(kBins, 0.0), observed(kBins, 0.0);
  double total = 0;
  for (const auto& f : fr) {
    const auto& xs = f.column("X");
    for (std::size_t i = 0; i < f.rows(); ++i) {
      total += xs[i];
      if (kind[i] != 0) {
        EXPECT_EQ(xs[i], 0) << "wall particle " << i;
        continue;
      }
      const int b = static_cast<int>((std::hypot(x[i], y[i]) - kR) / 0.25);
      if (b < 0 || b >= kBins) continue;
      observed[b] += xs[i];
      expected[b] += kJx / kJc * c[i] * m[i] / rho[i];
    }
  }
  const double n_mean = kRealizations * kJx * 2 * std::numbers::pi * kR * (1 - std::exp(-kK * kT));
  const double z_total = (total - n_mean) / std::sqrt(n_mean);
  // Bonferroni: 11 z-tests at a family-wise rate of 1e-3: |z| <= Phi^-1(1 - 1e-3 / 22) = 3.91.
  constexpr double kZ = 3.91;
  std::printf("stochastic total over %d realizations: %.0f against %.1f (z = %.2f)\n",
              kRealizations, total, n_mean, z_total);
  EXPECT_LE(std::fabs(z_total), kZ);
  double worst = 0;
  for (int b = 0; b < kBins; ++b) {
    const double z = (observed[b] - expected[b]) / std::sqrt(expected[b]);
    std::printf("  r in [%.2f, %.2f): %.0f against %.1f (z = %.2f)\n", kR + 0.25 * b,
                kR + 0.25 * (b + 1), observed[b], expected[b], z);
    EXPECT_GT(expected[b], 20.0);
    EXPECT_LE(std::fabs(z), kZ) << "bin " << b;
    worst = std::max(worst, std::fabs(z));
  }
  std::printf("max |z| over the bins %.2f (z* = %.2f)\n", worst, kZ);
  if (!HasFailure()) fs::remove_all(d);
}

#else
// Convergence of the deterministic profile (label validation): dx = 0.1, 0.05, 1/30 (R / dx =
// 5, 10, 15). The largest error sits in the first fluid layer, where the flux enters as a
// source spread over the particle's volume; the RMS over the fluid converges faster.
TEST(SurfaceFluxValidation, DiskProfileConvergesToTheBesselSolution) {
  double err[3], rms[3];
  const double dxs[3] = {0.1, 0.05, 1.0 / 30};
  for (int k = 0; k < 3; ++k) {
    const fs::path d = run_disk("conv" + std::to_string(k), dxs[k], 1);
    const auto files = frames(d / "out");
    ASSERT_FALSE(files.empty());
    const Profile p = deterministic_errors(read_csv(files.back()));
    err[k] = p.max_rel;
    rms[k] = p.rms_rel;
    EXPECT_LT(p.amount_rel, 1e-6);
    fs::remove_all(d);
  }
  std::printf(
      "disk: |C - c(r)| / c(R) at dx = 0.1, 0.05, 1/30: max %.3g %.3g %.3g, RMS %.3g %.3g %.3g "
      "(RMS orders %.2f %.2f)\n",
      err[0], err[1], err[2], rms[0], rms[1], rms[2], std::log2(rms[0] / rms[1]),
      std::log(rms[1] / rms[2]) / std::log(1.5));
  EXPECT_LT(err[1], err[0]);
  EXPECT_LT(err[2], err[1]);
  EXPECT_LT(rms[2], 0.6 * rms[0]);  // measured 0.30
  EXPECT_LT(err[2], 0.045);         // measured 0.032
  EXPECT_LT(rms[2], 0.0015);        // measured 0.00093
}
#endif

}  // namespace
}  // namespace sadr::e2e
