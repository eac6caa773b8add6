// SPDX-License-Identifier: MIT
// Lie and Strang splitting end to end, with a back-transfer from the SSA to
// the fluid (Boussinesq force from a stochastic species), over real processes.
//
// The scene: 32 SDPD particles on a periodic line at rest, k_B T = 0, each
// carrying 3125 molecules of A (N0 = 1e5) that decay, A -> 0 at rate lambda;
// the fluid feels the body acceleration a_i = beta C_i = beta n_i / V_i along
// +x. Pair forces conserve momentum exactly, so the total momentum is the
// time integral of the body force as the fluid sees it:
//   P = beta sum_stages tau_s sum_i n_i(t_s) rho_i(t_s) = beta rho0 S,
//   S = sum_s tau_s N(t_s),
// with N(t_s) the molecule count the fluid stage s received (rho_i = rho0 up
// to ~1e-9 here: the acceleration is uniform up to Poisson noise).
//  - Lie (fluid tau, SSA tau) uses N(t_k) over [t_k, t_k+1]: left Riemann sum.
//  - Strang (fluid tau/2, SSA tau, fluid tau/2) uses N(t_k) and N(t_k+1): the
//    trapezoid rule.
// Molecules die independently, alive at t_k with probability q^k, q =
// exp(-lambda tau), so E[S] and Var[S] are exact sums (below). With lambda tau
// = 0.2 the two rules differ by 10% (30 standard deviations), so each run is
// told apart from the other rule; each test is a z-test at |z| < 4.89
// (two-sided false-failure rate 1e-6).
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "cli_test_support.hpp"

namespace sadr::e2e {
namespace {

constexpr double kBeta = 1.0e-7;  // g beta [L^3/(T^2 molecules)] in 1D
constexpr double kLambda = 2.0;   // decay rate [1/T]
constexpr double kTau = 0.1;      // coupling step [T]
constexpr int kSteps = 10;        // end time 1.0
constexpr double kN0 = 32 * 3125.0;

std::string buoyancy_scene(const std::string& splitting, const std::string& outputs,
                           double checkpoint_every) {
  std::ostringstream s;
  s << "name: buoyancy\n"
       "dimension: 1\n"
       "box: {lower: [0.0], upper: [1.0], periodic: [true]}\n"
       "particles: {spacing: 0.03125, density: 1.0, fill: [{kind: fluid}]}\n"
       "fluid:\n"
       "  backend: sdpd\n"
       "  h_over_dx: 2.0\n"
       "  reference_density: 1.0\n"
       "  sound_speed: 1.0\n"
       "  shear_viscosity: 0.1\n"
       "  temperature: 0.0\n"
       "  boussinesq: {species: A, coefficient: "
    << kBeta
    << ", direction: [1.0]}\n"
       "species:\n"
       "  - {name: A, stochastic: true, diffusivity: 0.0, initial: [{count: 3125}]}\n"
       "reactions:\n"
       "  - {name: decay, equation: \"A -> 0\", rate: "
    << kLambda << "}\n"
    << "time: {coupling_step: " << kTau << ", end: " << kTau * kSteps
    << ", splitting: " << splitting << "}\n"
    << "output:\n  times: " << outputs << "\n  formats: [csv]\n";
  if (checkpoint_every > 0) s << "  checkpoint_every: " << checkpoint_every << "\n";
  s << "seed: 2024\n";
  return s.str();
}

/// Weights w_k of N(t_k), k = 0..kSteps, in S = sum_k w_k N(t_k).
std::vector<double> weights(bool strang) {
  std::vector<double> w(kSteps + 1, 0.0);
  for (int k = 0; k < kSteps; ++k) {
    if (strang) {
      w[k] += kTau / 2;
      w[k + 1] += kTau / 2;
    } else {
      w[k] += kTau;
    }
  }
  return w;
}

/// Exact mean and variance of S for N0 independent molecules with Exp(lambda) lifetimes.
std::pair<double, double> exact_moments(bool strang) {
  const auto w = weights(strang);
  const double q = std::exp(-kLambda * kTau);
  double m1 = 0, m2 = 0;  // one molecule: E[X], E[X^2], X = sum_k w_k 1{alive at t_k}
  for (int k = 0; k <= kSteps; ++k) {
    m1 += w[k] * std::pow(q, k);
    for (int l = 0; l <= kSteps; ++l) m2 += w[k] * w[l] * std::pow(q, std::max(k, l));
  }
  return {kN0 * m1, kN0 * (m2 - m1 * m1)};
}

double total_momentum(const CsvFrame& f) {
  const auto& m = f.column("mass");
  const auto& vx = f.column("vx");
  double p = 0;
  for (std::size_t i = 0; i < f.rows(); ++i) p += m[i] * vx[i];
  return p;
}

class Splitting : public ::testing::TestWithParam<const char*> {};

TEST_P(Splitting, MomentumFromStochasticBuoyancyMatchesTheQuadratureRule) {
  const std::string splitting = GetParam();
  const bool strang = splitting == "strang";
  const fs::path d = scratch("split-" + splitting);
  const fs::path scene = write_scene(d, buoyancy_scene(splitting, "[1.0]", 0));
  ASSERT_EQ(
      run(bin("sadr") + " run " + scene.string() + " -o " + (d / "out").string(), d / "run.log"), 0)
      << read_file(d / "run.log");
  // The plan says what it does: back-transfer of A, and Strang's two fluid calls.
  const std::string log = read_file(d / "run.log");
  EXPECT_NE(log.find("back-transfer"), std::string::npos) << log;
  const CsvFrame f = read_csv(frames(d / "out").back());  // t = 1.0
  ASSERT_EQ(f.rows(), 32u);
  double n_end = 0;
  for (double n : f.column("A")) n_end += n;
  const double s = total_momentum(f) / kBeta;  // rho0 = 1
  const auto [mean, var] = exact_moments(strang);
  const auto [other_mean, other_var] = exact_moments(!strang);
  const double z = (s - mean) / std::sqrt(var);
  const double z_other = (s - other_mean) / std::sqrt(other_var);
  std::printf(
      "%s: S = %.6f, exact E[S] = %.6f +- %.6f (z = %.2f); other rule %.6f (z = %.1f); "
      "continuous integral %.6f; N(T) = %.0f\n",
      splitting.c_str(), s, mean, std::sqrt(var), z, other_mean, z_other,
      kN0 * (1 - std::exp(-kLambda * kTau * kSteps)) / kLambda, n_end);
  EXPECT_LT(std::abs(z), 4.89) << "S = " << s << ", E[S] = " << mean;
  EXPECT_GT(std::abs(z_other), 4.89) << "indistinguishable from the other splitting";
  if (!HasFailure()) fs::remove_all(d);  // keep the evidence of a failure
}

INSTANTIATE_TEST_SUITE_P(LieAndStrang, Splitting, ::testing::Values("lie", "strang"));

TEST(StrangSplitting, ProcessesEmbeddedAndResumeGiveIdenticalFrames) {
  const fs::path d = scratch("strang-modes");
  const fs::path scene = write_scene(d, buoyancy_scene("strang", "[0.3, 0.6, 1.0]", 0.2));
  const std::string sadr = bin("sadr") + " ";
  ASSERT_EQ(run(sadr + "run " + scene.string() + " -q -o " + (d / "proc").string(), d / "a.log"), 0)
      << read_file(d / "a.log");
  ASSERT_EQ(run(sadr + "run " + scene.string() + " -q --embedded -o " + (d / "emb").string(),
                d / "b.log"),
            0)
      << read_file(d / "b.log");
  expect_same_frames(d / "proc", d / "emb");
  ASSERT_EQ(run(sadr + "run " + scene.string() + " -q --stop-at 0.5 -o " + (d / "half").string(),
                d / "c.log"),
            0)
      << read_file(d / "c.log");
  ASSERT_EQ(run(sadr + "resume " + (d / "half" / "checkpoint").string() + " -q", d / "d.log"), 0)
      << read_file(d / "d.log");
  expect_same_frames(d / "proc", d / "half");
  if (!HasFailure()) fs::remove_all(d);  // keep the evidence of a failure
}

}  // namespace
}  // namespace sadr::e2e
