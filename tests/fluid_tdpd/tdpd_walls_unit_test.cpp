// SPDX-License-Identifier: MIT
/// Unit tests of the effective walls (li2015 sec. II B; tdpd_walls.hpp):
///  - the paper's fits against the half-space integrals they approximate, computed here with
///    g(r) = 1 (the paper's g(r) of the a = 18.75 fluid is not available, so the tolerances
///    cover its effect; the measured ratios are printed). This is the evidence for the derived
///    combining prefactors (docs/tdpd.md);
///  - caps, Neumann total flux, Dirichlet sign, exact and bounded Dirichlet relaxation,
///    confinement, restore identity, rejections.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <vector>

#include "sadr/common/status.hpp"
#include "tdpd/tdpd_backend.hpp"
#include "tdpd/tdpd_walls.hpp"

namespace sadr::fluid {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kRc = 1.58;
constexpr double kRho = 4.0;

/// int_{s > h} f(r, s) dV over the half-space beyond a plane at distance h from the particle
/// (s = normal distance from the particle, r = distance), restricted to r < kRc.
double half_space(double h, const std::function<double(double, double)>& f) {
  const int ns = 200, nr = 200;
  auto simpson = [](int n, double a, double b, const std::function<double(double)>& g) {
    const double dx = (b - a) / n;
    double acc = g(a) + g(b);
    for (int k = 1; k < n; ++k) acc += (k % 2 ? 4.0 : 2.0) * g(a + k * dx);
    return acc * dx / 3.0;
  };
  return simpson(ns, h, kRc, [&](double s) {
    return simpson(nr, s, kRc, [&](double r) { return 2.0 * kPi * r * f(r, s); });
  });
}

tdpd::EffectiveWalls calibration_walls() {
  FluidModel m;
  m.box.dimension = 3;
  m.box.hi = {10.0, 4.0, 4.0};
  m.box.periodic = {false, true, true};
  m.smoothing_length = kRc;
  m.temperature = 1.0;
  tdpd::EffectiveWalls w;
  w.setup(m, 18.75, 4.5, kRc, kRho);
  return w;
}

TEST(TdpdWalls, DirichletPhiMatchesLinearExtrapolationIntegral) {
  // Derived: dC_i/dt = kappa rho int_{wall} w_DC (C_j - C_i) dV with the wall field extrapolated
  // linearly through C_w at the wall: C_j - C_i = (C_w - C_i) s / h, so the rate coefficient is
  // (rho / h) int w_DC s dV, which the fit reproduces as 2 pi rho phi(h).
  const auto w = calibration_walls();
  for (double q : {0.02, 0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 0.9}) {
    const double h = q * kRc;
    const double j =
        kRho / h * half_space(h, [](double r, double s) { return std::pow(1.0 - r / kRc, 2) * s; });
    const double ratio = 2.0 * kPi * kRho * w.phi(h) / j;
    std::printf("phi: h/r_cc = %.2f  2 pi rho phi / integral = %.4f\n", q, ratio);
    EXPECT_NEAR(ratio, 1.0, 0.07) << q;
  }
  EXPECT_EQ(w.phi(0.0), w.phi(0.01 * kRc));  // li2015 cap
  EXPECT_EQ(w.phi(kRc), 0.0);
}

TEST(TdpdWalls, PhibarMatchesNormalisedNormalFlux) {
  // Derived: Phi(h) = int_{wall} w_DC s dV (the flux a linear gradient would carry), normalised.
  const auto w = calibration_walls();
  auto phi_raw = [](double h) {
    return half_space(h, [](double r, double s) { return std::pow(1.0 - r / kRc, 2) * s; });
  };
  double norm = 0.0, fit_norm = 0.0;
  const int n = 100;
  for (int k = 0; k < n; ++k) {
    const double h = (k + 0.5) * kRc / n;
    norm += phi_raw(h) * kRc / n;
    fit_norm += w.phibar(h) * kRc / n;
  }
  EXPECT_NEAR(fit_norm, 1.0, 0.01);  // the fit is normalised to 0.9%
  for (double q : {0.0, 0.1, 0.3, 0.5, 0.7}) {
    const double h = q * kRc;
    std::printf("phibar: h/r_cc = %.1f fit %.4f integral %.4f\n", q, w.phibar(h),
                phi_raw(h) / norm);
    EXPECT_NEAR(w.phibar(h), phi_raw(h) / norm, 0.12) << q;
  }
}

TEST(TdpdWalls, ForceFitsMatchHalfSpaceIntegrals) {
  // f_C = a rho int w_C (s / r) dV; gamma_tau, gamma_n = (gamma rho / h) int w_D e_k^2 s dV with
  // the wall velocity extrapolated linearly (v_i - v_j = v_i s / h), e_k the tangential / normal
  // component of the unit pair vector (azimuthal average (1 - s^2/r^2)/2 and s^2/r^2).
  const auto w = calibration_walls();
  const double a = 18.75, gamma = 4.5, s1 = 0.41;
  for (double q : {0.1, 0.2, 0.3, 0.5}) {
    const double h = q * kRc;
    const double fc =
        a * kRho * half_space(h, [](double r, double s) { return (1.0 - r / kRc) * s / r; });
    const double gt = gamma * kRho / h * half_space(h, [&](double r, double s) {
                        return std::pow(1.0 - r / kRc, s1) * 0.5 * (1.0 - s * s / (r * r)) * s;
                      });
    const double gn = gamma * kRho / h * half_space(h, [&](double r, double s) {
                        return std::pow(1.0 - r / kRc, s1) * s * s / (r * r) * s;
                      });
    std::printf("h/r_c = %.1f: f_C fit/int %.3f  gamma_tau %.3f  gamma_n %.3f\n", q, w.f_c(h) / fc,
                w.gamma_tau(h) / gt, w.gamma_n(h) / gn);
    EXPECT_NEAR(w.f_c(h) / fc, 1.0, 0.25) << q;
    EXPECT_NEAR(w.gamma_tau(h) / gt, 1.0, 0.1) << q;
    EXPECT_NEAR(w.gamma_n(h) / gn, 1.0, 0.1) << q;
  }
  EXPECT_EQ(w.gamma_tau(0.0), w.gamma_tau(0.05 * kRc));  // li2015 caps
  EXPECT_EQ(w.gamma_n(0.0), w.gamma_n(0.1 * kRc));
  EXPECT_NEAR(w.f_c(0.0), 73.5543, 1e-3);  // sum of the paper's coefficients
}

struct SmallChannel {
  FluidModel model;
  ParticleState state;
  SmallChannel() {
    const double sp = 0.63;
    model.box.dimension = 3;
    model.box.hi = {8 * sp, 6 * sp, 6 * sp};
    model.box.periodic = {false, true, true};
    model.smoothing_length = kRc;
    model.reference_density = kRho;
    model.temperature = 1.0;
    model.seed = 5;
    model.backend_parameters["effective_walls"] = 1.0;
    model.species.push_back({"C", 2.0, true, {}, {}});
    model.wall_regions.resize(2);
    model.wall_regions[0].inward_normal = {1, 0, 0};
    model.wall_regions[1].inward_normal = {-1, 0, 0};
    model.species[0].wall_conditions = {{WallCondition::Type::kNeumann, 0.05},
                                        {WallCondition::Type::kDirichlet, 1.0}};
    state.dimension = 3;
    state.resize(8 * 36, true);
    for (std::size_t i = 0; i < state.size(); ++i) {
      const double c[3] = {static_cast<double>(i % 8), static_cast<double>((i / 8) % 6),
                           static_cast<double>(i / 48)};
      for (int k = 0; k < 3; ++k) {
        state.positions[3 * i + k] = (c[k] + 0.5) * sp;
        state.velocities[3 * i + k] = 0.3 * std::sin(1.7 * static_cast<double>(3 * i + k));
      }
    }
  }
};

TEST(TdpdWalls, NeumannTotalAndDirichletSign) {
  SmallChannel ch;
  // C uniform: the pair fluxes vanish, only the wall terms remain
  TdpdBackend b;
  b.initialize(ch.model, ch.state, {std::vector<double>(ch.state.size(), 0.5)});
  std::vector<double> f;
  std::vector<std::vector<double>> q;
  b.evaluate_current(0, 0.01, f, q);
  double neumann = 0.0;
  for (std::size_t i = 0; i < ch.state.size(); ++i) {
    const double x = ch.state.positions[3 * i];
    if (x < 0.5 * ch.model.box.hi[0]) {
      neumann += q[0][i];
      EXPECT_GE(q[0][i], 0.0);
    } else {
      EXPECT_GE(q[0][i], 0.0);  // C = 0.5 < C_w = 1: flux into the particle
    }
  }
  // sum_i dC_i/dt = q A N / V (the amount sum_i C_i V_i grows at q A).
  const auto& box = ch.model.box;
  const double area = box.length(1) * box.length(2);
  const double nv = static_cast<double>(ch.state.size()) / (area * box.length(0));
  EXPECT_NEAR(neumann, 0.05 * area * nv, 1e-12);
}

TEST(TdpdWalls, ConfinedAndRestoreIdentical) {
  SmallChannel ch;
  TdpdBackend a;
  a.initialize(ch.model, ch.state, {});
  for (std::uint64_t s = 0; s < 30; ++s) a.advance(s, 0.01);
  const std::string blob = a.save();
  for (std::uint64_t s = 30; s < 50; ++s) a.advance(s, 0.01);
  TdpdBackend b;
  b.initialize(ch.model, ch.state, {});
  b.restore(blob);
  for (std::uint64_t s = 30; s < 50; ++s) b.advance(s, 0.01);
  ParticleState sa, sb;
  a.read_state(sa);
  b.read_state(sb);
  EXPECT_EQ(sa.positions, sb.positions);
  EXPECT_EQ(a.concentrations(0), b.concentrations(0));
  for (std::size_t i = 0; i < sa.size(); ++i) {
    EXPECT_GE(sa.positions[3 * i], 0.0);
    EXPECT_LE(sa.positions[3 * i], ch.model.box.hi[0]);
  }
}

TEST(TdpdWalls, InflowBufferHoldsValueAndSeamIsCut) {
  SmallChannel ch;
  ch.model.species[0].wall_conditions.clear();  // no-flux walls: the buffer is the only source
  ch.model.backend_parameters["buffer_axis"] = 1.0;
  ch.model.backend_parameters["inflow_length"] = 1.0;
  ch.model.backend_parameters["inflow_value"] = 2.0;
  TdpdBackend b;
  b.initialize(ch.model, ch.state, {});
  std::vector<double> f;
  std::vector<std::vector<double>> q;
  b.evaluate_current(0, 0.01, f, q);
  int near = 0;
  for (std::size_t i = 0; i < ch.state.size(); ++i) {
    const double y = ch.state.positions[3 * i + 1];
    if (y < 1.0) {
      EXPECT_EQ(b.concentrations(0)[i], 2.0);
      EXPECT_EQ(q[0][i], 0.0);
    } else if (y >= 1.0 + kRc) {
      EXPECT_EQ(q[0][i], 0.0) << "y = " << y;  // reached only through the cut seam
    } else {
      near += q[0][i] > 0.0 ? 1 : 0;
    }
  }
  EXPECT_GT(near, 0);
  ch.model.backend_parameters["buffer_axis"] = 0.0;  // a walled axis
  EXPECT_THROW(b.initialize(ch.model, ch.state, {}), InvalidArgument);
}

TEST(TdpdNoise, UniformPairNoiseHasUnitVarianceAndIsBounded) {
  // FluidModel::noise = kUniform: xi = sqrt(3) (2u - 1). One pair at r = 0.5 along x, v = 0,
  // no conservative force (a = 0): F_x = sigma w_R xi / sqrt(dt).
  FluidModel m;
  m.box.dimension = 3;
  m.box.hi = {6.0, 6.0, 6.0};
  m.box.periodic = {true, true, true};
  m.smoothing_length = kRc;
  m.reference_density = kRho;
  m.temperature = 1.0;
  m.noise = NoiseDistribution::kUniform;
  m.backend_parameters["a"] = 0.0;
  ParticleState st;
  st.dimension = 3;
  st.resize(2, true);
  st.positions = {1.0, 1.0, 1.0, 1.5, 1.0, 1.0};
  st.velocities.assign(6, 0.0);
  TdpdBackend b;
  b.initialize(m, st, {});
  const double dt = 0.01;
  const double scale = std::sqrt(2.0 * 4.5) * std::pow(1.0 - 0.5 / kRc, 0.205) / std::sqrt(dt);
  double sum = 0.0, sum2 = 0.0, amax = 0.0;
  const int n = 4000;
  std::vector<double> f;
  std::vector<std::vector<double>> q;
  for (int k = 0; k < n; ++k) {
    b.evaluate_current(static_cast<std::uint64_t>(k), dt, f, q);
    const double xi = -f[0] / scale;  // e_01 = -e_x for particle 0
    EXPECT_NEAR(f[0], -f[3], 1e-12);
    sum += xi;
    sum2 += xi * xi;
    amax = std::max(amax, std::abs(xi));
  }
  // Var(xi^2) = 4/5 for the uniform law: SE of the mean square 0.014, of the mean 0.016.
  EXPECT_NEAR(sum2 / n, 1.0, 0.06);
  EXPECT_NEAR(sum / n, 0.0, 0.065);
  EXPECT_LE(amax, std::sqrt(3.0) + 1e-12);
}

/// Particles at rest (a = gamma = k_B T = 0) next to a Dirichlet wall C_w = 1, kappa = 8.68 and
/// dt = 0.01 as in the Pe = 10 Poiseuille case (k dt = kappa 2 pi rho phi(h) dt = 6.8 at the phi
/// cap h = 0.01 r_cc). The wall relaxation must keep every C_i within [min, max] of the initial
/// values and C_w (maximum principle) and converge to C_w. Before the fix the wall term entered
/// the explicit half-kicks as a flux: the midpoint values followed explicit Euler with factor
/// 2 exp(-k dt/2) - 1 (-> -1), overshooting C_w and, with the pair diffusion, oscillating.
struct WallRelaxCase {
  std::vector<double> h;   // distances from the upper wall [r_cc]
  std::vector<double> y;   // in-plane coordinate [length]
  std::vector<double> c0;  // initial concentrations
};

/// Runs `steps` steps of 0.01; returns the final concentrations and the largest excursion
/// outside [min, max] of the initial values and C_w over all steps.
std::vector<double> run_wall_relax(const WallRelaxCase& wc, int steps, double& worst_excess,
                                   double* k_rate0 = nullptr) {
  FluidModel m;
  m.box.dimension = 3;
  m.box.hi = {6.0, 6.0, 6.0};
  m.box.periodic = {false, true, true};
  m.smoothing_length = kRc;
  m.reference_density = kRho;
  m.temperature = 0.0;
  m.seed = 3;
  m.backend_parameters = {{"effective_walls", 1.0}, {"a", 0.0}, {"gamma", 0.0}};
  m.wall_regions.resize(2);
  m.wall_regions[0].inward_normal = {1, 0, 0};
  m.wall_regions[1].inward_normal = {-1, 0, 0};
  m.species.push_back({"C", 8.68, true, {}, {}});
  m.species[0].wall_conditions = {{WallCondition::Type::kNoFlux, 0.0},
                                  {WallCondition::Type::kDirichlet, 1.0}};
  ParticleState st;
  st.dimension = 3;
  st.resize(wc.h.size(), true);
  for (std::size_t i = 0; i < wc.h.size(); ++i) {
    st.positions[3 * i] = m.box.hi[0] - wc.h[i] * kRc;
    st.positions[3 * i + 1] = wc.y[i];
    st.positions[3 * i + 2] = 3.0;
    for (int k = 0; k < 3; ++k) st.velocities[3 * i + k] = 0.0;
  }
  double lo = 1.0, hi = 1.0;
  for (const double c : wc.c0) {
    lo = std::min(lo, c);
    hi = std::max(hi, c);
  }
  TdpdBackend b;
  b.initialize(m, st, {wc.c0});
  if (k_rate0) *k_rate0 = 8.68 * 2.0 * kPi * kRho * b.effective_walls().phi(wc.h[0] * kRc);
  worst_excess = 0.0;
  for (std::uint64_t s = 0; s < static_cast<std::uint64_t>(steps); ++s) {
    const StepReport rep = b.advance(s, 0.01);
    EXPECT_EQ(rep.substeps, 1u);
    for (const double c : b.concentrations(0)) {
      worst_excess = std::max({worst_excess, c - hi, lo - c});
    }
  }
  b.read_state(st);
  for (std::size_t i = 0; i < wc.h.size(); ++i) {  // at rest: the distances did not change
    EXPECT_NEAR(st.positions[3 * i], m.box.hi[0] - wc.h[i] * kRc, 1e-12);
  }
  return b.concentrations(0);
}

TEST(TdpdWalls, DirichletRelaxationBoundedAndConverges) {
  // Before the fix: case 0 exceeded C_w by 1.0e-3, case 2 by 1.3e-2 (still 4e-3 off C_w after
  // 300 steps), case 3 oscillated with amplitude 0.67 that had not decayed after 300 steps.
  const WallRelaxCase cases[] = {
      {{0.01}, {3.0}, {0.0}},                                // at the phi cap: k dt = 6.8
      {{0.2}, {3.0}, {0.0}},                                 // k dt = 0.29
      {{0.01, 0.02}, {3.0, 3.2}, {0.0, 0.4}},                // k dt = 6.8, 3.4 + pair diffusion
      {{0.01, 0.3, 0.02}, {3.0, 3.3, 2.6}, {0.0, 0.0, 0.3}}  // k dt = 6.8, 0.15, 3.4
  };
  for (std::size_t k = 0; k < std::size(cases); ++k) {
    double excess = 0.0;
    const std::vector<double> c = run_wall_relax(cases[k], 300, excess);
    double dev = 0.0;
    for (const double ci : c) dev = std::max(dev, std::abs(ci - 1.0));
    std::printf("wall relax case %zu: max excess over [min, max] %.3e, final |C - C_w| %.3e\n", k,
                excess, dev);
    EXPECT_LE(excess, 1e-12) << "case " << k;
    EXPECT_LT(dev, 1e-6) << "case " << k;
  }
  // A lone particle has no pair flux: C(t) = C_w + (C(0) - C_w) exp(-k t) exactly.
  for (const double h : {0.01, 0.05, 0.2, 0.5}) {
    double excess = 0.0, k_rate = 0.0;
    const std::vector<double> c = run_wall_relax({{h}, {3.0}, {0.0}}, 3, excess, &k_rate);
    EXPECT_NEAR(c[0], 1.0 - std::exp(-k_rate * 0.03), 1e-12) << "h = " << h << " r_cc";
  }
}

TEST(TdpdWalls, Rejections) {
  SmallChannel ch;
  TdpdBackend b;
  ch.model.backend_parameters["effective_walls"] = 2.0;
  EXPECT_THROW(b.initialize(ch.model, ch.state, {}), InvalidArgument);
  ch.model.backend_parameters["effective_walls"] = 1.0;
  ch.model.box.periodic = {true, true, true};
  EXPECT_THROW(b.initialize(ch.model, ch.state, {}), InvalidArgument);
}

}  // namespace
}  // namespace sadr::fluid
