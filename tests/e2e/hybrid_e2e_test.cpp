// SPDX-License-Identifier: MIT
// Laws of the time t and hybrid reactions end to end (docs/method.md section 4c),
// through the orchestrator and both services: static particles without diffusion,
// so every particle is an independent well-mixed reactor.
//  - deterministic dC/dt = -k exp(-a t) C against C0 exp(-k (1 - exp(-a t)) / a);
//  - stochastic 0 -> A at k1 exp(-a t) (t held at each SSA stage's start) against the
//    mean of that piecewise-constant rate (Poisson);
//  - the linear hybrid case: stochastic A birth-death (0 -> A at k1, A -> 0 at d1),
//    deterministic B with dB/dt = k A - d B (the fluid reads A = X / V), stochastic C
//    with 0 -> C at kc B (the SSA reads B, frozen over each stage): E[A], E[B], E[C]
//    at T against their closed forms, z-tests over the independent particles.
//  - the same chain on sdpd (particles at rest, k_B T = 0: the graph rebuilt and the
//    geometry sent every step, with the frozen concentrations next to it).
// False failures: 8 z-tests at |z| <= 4.4 (two-sided 1.1e-5 each, 8.6e-5 in all, plus
// the splitting bias of B and C, below 0.2 sigma: about 1e-4 family-wise).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "cli_test_support.hpp"

namespace sadr::e2e {
namespace {

constexpr double kZ = 4.4;

fs::path run_scene(const std::string& name, const std::string& text) {
  const fs::path d = scratch("hybrid-" + name);
  const fs::path s = write_scene(d, text);
  EXPECT_EQ(run(bin("sadr") + " run " + s.string() + " --embedded -o " + (d / "out").string(),
                d / "run.log"),
            0)
      << read_file(d / "run.log");
  return d;
}

struct Moments {
  double mean = 0, sd_of_mean = 0;
};
Moments moments(const std::vector<double>& x) {
  double m = 0;
  for (double v : x) m += v;
  m /= static_cast<double>(x.size());
  double s2 = 0;
  for (double v : x) s2 += (v - m) * (v - m);
  s2 /= static_cast<double>(x.size() - 1);
  return {m, std::sqrt(s2 / static_cast<double>(x.size()))};
}

TEST(HybridE2e, LawsOfTimeInBothPathsMatchTheirExactSolutions) {
  // 1000 particles of V = 1; C deterministic, A stochastic (no reactant: Poisson counts).
  const double k = 1.5, a = 2.0, c0 = 3.0, k1 = 5.0, tau = 0.1, t_end = 1.0;
  const std::string text = R"Y(name: time_laws
dimension: 1
box: {lower: [0.0], upper: [1000.0], periodic: [true]}
particles: {spacing: 1.0}
fluid: {backend: static, h_over_dx: 2.0, max_time_step: 0.001}
parameters: {k: 1.5, a: 2.0, k1: 5.0}
species:
  - {name: C, stochastic: false, diffusivity: 0, initial: [{concentration: 3.0}]}
  - {name: A, diffusivity: 0}
reactions:
  - {name: decay, equation: "C -> 0", law: {type: expression, expression: "k*exp(-a*t)*C"}}
  - {name: birth, equation: "0 -> A", law: {type: expression, expression: "k1*exp(-a*t)"}}
time: {coupling_step: 0.1, end: 1.0}
output: {every: 1.0, formats: [csv]}
seed: 5
)Y";
  const fs::path d = run_scene("time", text);
  const std::string log = read_file(d / "run.log");
  EXPECT_NE(log.find("ssa laws of t: t held at each SSA stage's start"), std::string::npos) << log;
  const CsvFrame f = read_csv(frames(d / "out").back());
  const double exact = c0 * std::exp(-k * (1 - std::exp(-a * t_end)) / a);
  double worst = 0;
  for (double v : f.column("C")) worst = std::max(worst, std::fabs(v - exact));
  EXPECT_LT(worst, 1e-7 * c0);
  // The SSA holds t at each stage's start: E[X] = V sum_k k1 exp(-a t_k) tau.
  double held = 0;
  for (int s = 0; s < 10; ++s) held += k1 * std::exp(-a * s * tau) * tau;
  const double continuous = k1 * (1 - std::exp(-a * t_end)) / a;
  const Moments m = moments(f.column("A"));
  const double z = (m.mean - held) / std::sqrt(held / 1000.0);  // Poisson variance
  std::printf(
      "C(t=1) error %.3g; A mean %.4f, held-t mean %.4f (z = %.2f), continuous %.4f "
      "(held-t bias %.3f = first order in tau)\n",
      worst, m.mean, held, z, continuous, held - continuous);
  EXPECT_LT(std::fabs(z), kZ);
  if (!HasFailure()) fs::remove_all(d);
}

TEST(HybridE2e, LinearBirthDeathDrivesDeterministicBAndBackIntoStochasticC) {
  const double k1 = 20, d1 = 1, k = 1, d = 2, kc = 0.5, T = 2, tau = 0.005;
  const int n = 2000;
  const std::string text = R"Y(name: hybrid_linear
dimension: 1
box: {lower: [0.0], upper: [2000.0], periodic: [true]}
particles: {spacing: 1.0}
fluid: {backend: static, h_over_dx: 2.0, max_time_step: 0.005}
parameters: {k: 1.0, kc: 0.5}
species:
  - {name: A, diffusivity: 0}
  - {name: B, stochastic: false, diffusivity: 0}
  - {name: C, diffusivity: 0}
reactions:
  - {name: a_birth, equation: "0 -> A", rate: 20.0}
  - {name: a_death, equation: "A -> 0", rate: 1.0}
  - {name: b_birth, equation: "0 -> B", law: {type: expression, expression: "k*A"}}
  - {name: b_death, equation: "B -> 0", rate: 2.0}
  - {name: c_birth, equation: "0 -> C", law: {type: expression, expression: "kc*B"}}
time: {coupling_step: 0.005, end: 2.0}
output: {every: 2.0, formats: [csv]}
seed: 17
)Y";
  const fs::path dir = run_scene("linear", text);
  const std::string log = read_file(dir / "run.log");
  EXPECT_NE(log.find("back-transfer ssa -> fluid: A"), std::string::npos) << log;
  EXPECT_NE(log.find("hybrid fluid -> ssa: B"), std::string::npos) << log;
  const CsvFrame f = read_csv(frames(dir / "out").back());
  ASSERT_EQ(f.rows(), static_cast<std::size_t>(n));
  // Closed forms (V = 1): E[A] = m (1 - e^{-d1 t}), m = k1/d1;
  // E[B] = k m [(1 - e^{-d t})/d - (e^{-d1 t} - e^{-d t})/(d - d1)];
  // E[C] = kc int_0^T E[B] dt.
  const double m = k1 / d1;
  const double ea = m * (1 - std::exp(-d1 * T));
  const double eb =
      k * m * ((1 - std::exp(-d * T)) / d - (std::exp(-d1 * T) - std::exp(-d * T)) / (d - d1));
  const double int_b = k * m *
                       ((T - (1 - std::exp(-d * T)) / d) / d -
                        ((1 - std::exp(-d1 * T)) / d1 - (1 - std::exp(-d * T)) / d) / (d - d1));
  const double ec = kc * int_b;
  const struct {
    const char* name;
    double exact;
  } rows[] = {{"A", ea}, {"B", eb}, {"C", ec}};
  for (const auto& r : rows) {
    const Moments mo = moments(f.column(r.name));
    const double z = (mo.mean - r.exact) / mo.sd_of_mean;
    std::printf("E[%s](T=2): %.5f +- %.5f, exact %.5f, z = %.2f\n", r.name, mo.mean, mo.sd_of_mean,
                r.exact, z);
    EXPECT_LT(std::fabs(z), kZ) << r.name;
  }
  (void)tau;
  if (!HasFailure()) fs::remove_all(dir);
}

TEST(HybridE2e, TheChainOnAMovingBackendMatchesTheSameMeans) {
  // 1600 particles of V = 0.25 (2D, spacing 0.5) at rest on sdpd: E[X_A] = V E[a], etc.
  const double k1 = 80, d1 = 1, k = 1, d = 2, kc = 0.5, T = 2, v = 0.25;
  const std::string text = R"Y(name: hybrid_sdpd
dimension: 2
box: {lower: [0.0, 0.0], upper: [20.0, 20.0], periodic: [true, true]}
particles: {spacing: 0.5}
fluid: {backend: sdpd, h_over_dx: 2.0, temperature: 0.0, sound_speed: 2.0, shear_viscosity: 0.1}
parameters: {k: 1.0, kc: 0.5}
species:
  - {name: A, diffusivity: 0}
  - {name: B, stochastic: false, diffusivity: 0}
  - {name: C, diffusivity: 0}
reactions:
  - {name: a_birth, equation: "0 -> A", rate: 80.0}
  - {name: a_death, equation: "A -> 0", rate: 1.0}
  - {name: b_birth, equation: "0 -> B", law: {type: expression, expression: "k*A"}}
  - {name: b_death, equation: "B -> 0", rate: 2.0}
  - {name: c_birth, equation: "0 -> C", law: {type: expression, expression: "kc*B"}}
time: {coupling_step: 0.01, end: 2.0}
output: {every: 2.0, formats: [csv]}
seed: 17
)Y";
  const fs::path dir = run_scene("sdpd", text);
  const std::string log = read_file(dir / "run.log");
  EXPECT_NE(log.find("graph rebuilt every step"), std::string::npos) << log;
  const CsvFrame f = read_csv(frames(dir / "out").back());
  const double m = k1 / d1;
  const double eb =
      k * m * ((1 - std::exp(-d * T)) / d - (std::exp(-d1 * T) - std::exp(-d * T)) / (d - d1));
  const double int_b = k * m *
                       ((T - (1 - std::exp(-d * T)) / d) / d -
                        ((1 - std::exp(-d1 * T)) / d1 - (1 - std::exp(-d * T)) / d) / (d - d1));
  const struct {
    const char* name;
    double exact;
  } rows[] = {{"A", v * m * (1 - std::exp(-d1 * T))}, {"B", eb}, {"C", v * kc * int_b}};
  for (const auto& r : rows) {
    const Moments mo = moments(f.column(r.name));
    const double z = (mo.mean - r.exact) / mo.sd_of_mean;
    std::printf("sdpd E[%s](T=2): %.5f +- %.5f, exact %.5f, z = %.2f\n", r.name, mo.mean,
                mo.sd_of_mean, r.exact, z);
    EXPECT_LT(std::fabs(z), kZ) << r.name;
  }
  if (!HasFailure()) fs::remove_all(dir);
}

TEST(HybridE2e, AStoppedAndResumedHybridRunEqualsTheFullRun) {
  // Both crossings (A -> fluid, B -> SSA) and a law of t, with services as child
  // processes: the SSA snapshot keeps the frozen inputs, so the resumed run continues
  // bit-identically.
  const std::string text = R"Y(name: hybrid_resume
dimension: 1
box: {lower: [0.0], upper: [200.0], periodic: [true]}
particles: {spacing: 1.0}
fluid: {backend: static, h_over_dx: 2.0, max_time_step: 0.01}
parameters: {k: 1.0, kc: 0.5}
species:
  - {name: A, diffusivity: 0}
  - {name: B, stochastic: false, diffusivity: 0}
  - {name: C, diffusivity: 0}
reactions:
  - {name: a_birth, equation: "0 -> A", rate: 20.0}
  - {name: a_death, equation: "A -> 0", rate: 1.0}
  - {name: b_birth, equation: "0 -> B", law: {type: expression, expression: "k*A"}}
  - {name: b_death, equation: "B -> 0", rate: 2.0}
  - {name: c_birth, equation: "0 -> C", law: {type: expression, expression: "kc*B*exp(-t)"}}
time: {coupling_step: 0.05, end: 1.0}
output: {every: 0.25, formats: [csv]}
seed: 31
)Y";
  const fs::path d = scratch("hybrid-resume");
  const fs::path scene = write_scene(d, text);
  const std::string sadr = bin("sadr") + " ";
  ASSERT_EQ(run(sadr + "run " + scene.string() + " -q -o " + (d / "full").string(), d / "a.log"), 0)
      << read_file(d / "a.log");
  ASSERT_EQ(run(sadr + "run " + scene.string() + " -q --stop-at 0.5 -o " + (d / "half").string(),
                d / "b.log"),
            0)
      << read_file(d / "b.log");
  ASSERT_EQ(run(sadr + "resume " + (d / "half" / "checkpoint").string() + " -q", d / "c.log"), 0)
      << read_file(d / "c.log");
  expect_same_frames(d / "full", d / "half");
  if (!HasFailure()) fs::remove_all(d);
}

TEST(HybridE2e, TheSplittingBiasOfBIsFirstOrderInTheCouplingStep) {
  // The reduced bench/hybrid/tau_sweep.py: A, B only, so the SSA of A is the same path at
  // every tau (no law of A reads B or t) and differences between taus carry no noise.
  auto mean_b = [](double tau) {
    const std::string text = R"Y(name: hybrid_tau
dimension: 1
box: {lower: [0.0], upper: [500.0], periodic: [true]}
particles: {spacing: 1.0}
fluid: {backend: static, h_over_dx: 2.0, max_time_step: 0.001}
parameters: {k: 1.0}
species:
  - {name: A, diffusivity: 0}
  - {name: B, stochastic: false, diffusivity: 0}
reactions:
  - {name: a_birth, equation: "0 -> A", rate: 20.0}
  - {name: a_death, equation: "A -> 0", rate: 1.0}
  - {name: b_birth, equation: "0 -> B", law: {type: expression, expression: "k*A"}}
  - {name: b_death, equation: "B -> 0", rate: 2.0}
time: {coupling_step: )Y" + std::to_string(tau) +
                             R"Y(, end: 2.0}
output: {every: 2.0, formats: [csv]}
seed: 29
)Y";
    const fs::path d = run_scene("tau-" + std::to_string(tau), text);
    const double m = moments(read_csv(frames(d / "out").back()).column("B")).mean;
    fs::remove_all(d);
    return m;
  };
  const double b1 = mean_b(0.2), b2 = mean_b(0.1), b3 = mean_b(0.05);
  const double order = std::log2((b1 - b2) / (b2 - b3));
  std::printf("B(0.2) %.6f, B(0.1) %.6f, B(0.05) %.6f: observed order %.3f\n", b1, b2, b3, order);
  EXPECT_LT(b1, b2);  // frozen at the step's start: B lags, the bias is negative
  EXPECT_GT(order, 0.85);
  EXPECT_LT(order, 1.25);
}

}  // namespace
}  // namespace sadr::e2e
