// SPDX-License-Identifier: MIT
/// Validation of the tDPD backend (ctest label "validation", minutes):
///  - 1D step diffusion (li2015 sec. III A) with D = 0.05 and 0.5 in a periodic
///    slab (two interfaces; the erf solution summed over periodic images), and the effective D
///    fitted to the particle concentrations against li2015's calibration D = 0.0187 + 0.771 kappa;
///  - D(kappa) by the reverse-Poiseuille method of li2015 sec. II A: a source +s in one half of a
///    periodic box and -s in the other gives the steady profile D C'' = -/+ s, a parabola in
///    each half whose curvature gives D.
/// Parameters: rho = 4, k_B T = 1, a = 18.75, gamma = 4.5 (sigma = 3), r_c = r_cc = 1.58,
/// s1 = 0.41, dt = 0.01. Measured numbers are printed and recorded as test properties.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

#include "sadr/common/rng.hpp"
#include "tdpd/tdpd_backend.hpp"
#include "tdpd_lattice.hpp"

namespace sadr::fluid {
namespace {

constexpr double kSpacing = 0.6299605249474366;  // 4^(-1/3): number density 4

double d_of_kappa(double kappa) {
  return 0.0187 + 0.771 * kappa;
}
double kappa_of_d(double d) {
  return (d - 0.0187) / 0.771;
}

/// Periodic slab nx x ny x ny lattice cells (jittered), species given by diffusivities (kappa).
struct Slab {
  FluidModel model;
  ParticleState state;
  double lx = 0;
  Slab(int nx, int ny, const std::vector<double>& kappas, std::uint64_t seed) {
    lx = nx * kSpacing;
    const double ly = ny * kSpacing;
    model.box.dimension = 3;
    model.box.hi = {lx, ly, ly};
    model.box.periodic = {true, true, true};
    model.smoothing_length = 1.58;
    model.reference_density = 4.0;
    model.temperature = 1.0;
    model.seed = seed;
    for (std::size_t s = 0; s < kappas.size(); ++s) {
      SpeciesSpec sp;
      sp.def.name = "S";
      sp.def.name += std::to_string(s);
      sp.def.diffusivity = kappas[s];
      model.species.push_back(sp);
    }
    test::fill_jittered_lattice(state, nx, ny, ny, kSpacing, seed, /*thermal=*/false);
    state.densities.assign(state.size(), 4.0);
    state.masses.assign(state.size(), 1.0);
  }
};

/// C = 1 on [0, L/2), 0 on [L/2, L) at t = 0, periodic, diffused with D for time t.
double periodic_step(double x, double t, double d, double l) {
  const double s = 2.0 * std::sqrt(d * t);
  double c = 0.0;
  for (int n = -3; n <= 3; ++n) {
    c += 0.5 * (std::erf((x - n * l) / s) - std::erf((x - 0.5 * l - n * l) / s));
  }
  return c;
}

double golden_min(const std::function<double(double)>& f, double lo, double hi) {
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double a = lo, b = hi, c = b - g * (b - a), d = a + g * (b - a);
  double fc = f(c), fd = f(d);
  for (int it = 0; it < 60; ++it) {
    if (fc < fd) {
      b = d, d = c, fd = fc, c = b - g * (b - a), fc = f(c);
    } else {
      a = c, c = d, fc = fd, d = a + g * (b - a), fd = f(d);
    }
  }
  return 0.5 * (a + b);
}

TEST(TdpdValidation, StepDiffusionAgainstErf) {
  const std::vector<double> targets = {0.05, 0.5};
  Slab slab(64, 6, {kappa_of_d(targets[0]), kappa_of_d(targets[1])}, 2024);
  TdpdBackend b;
  b.initialize(slab.model, slab.state, {});
  std::uint64_t step = 0;
  for (; step < 200; ++step) b.advance(step, 0.01);  // thermalise the fluid first
  ParticleState st;
  b.read_state(st);
  const std::size_t n = st.size();
  std::vector<double> c1(n), c2(n);
  for (std::size_t i = 0; i < n; ++i) {
    c1[i] = st.positions[3 * i] < 0.5 * slab.lx ? 1.0 : 0.0;
    c2[i] = 1.0 - c1[i];
  }
  b.set_concentrations(0, c1);
  b.set_concentrations(1, c2);
  const double t0 = b.time();
  const std::vector<double> outputs = {5.0, 10.0, 20.0};
  for (double tout : outputs) {
    while (b.time() - t0 < tout - 1e-9) b.advance(step++, 0.01);
    b.read_state(st);
    const double t = b.time() - t0;
    for (int s = 0; s < 2; ++s) {
      const double d = targets[s];
      const auto& c = b.concentrations(s);
      auto ref = [&](std::size_t i, double dd) {
        const double r = periodic_step(st.positions[3 * i], t, dd, slab.lx);
        return s == 0 ? r : 1.0 - r;
      };
      // Bin errors (64 bins along x): mean over the particles of a bin of C_i - C_ref(x_i).
      const int nb = 64;
      std::vector<double> err(nb, 0.0), cnt(nb, 0.0);
      double sse = 0;
      for (std::size_t i = 0; i < n; ++i) {
        const int k = std::min(nb - 1, static_cast<int>(st.positions[3 * i] / slab.lx * nb));
        const double e = c[i] - ref(i, d);
        err[k] += e;
        cnt[k] += 1;
        sse += e * e;
      }
      double emax = 0, ebin2 = 0;
      for (int k = 0; k < nb; ++k) {
        const double e = cnt[k] > 0 ? err[k] / cnt[k] : 0.0;
        emax = std::max(emax, std::abs(e));
        ebin2 += e * e;
      }
      const double d_fit = golden_min(
          [&](double dd) {
            double acc = 0;
            for (std::size_t i = 0; i < n; ++i) acc += std::pow(c[i] - ref(i, dd), 2);
            return acc;
          },
          0.3 * d, 3.0 * d);
      std::printf(
          "step D=%.2f t=%.0f: particle RMS err %.4f, bin max err %.4f, bin RMS err %.4f, "
          "fitted D %.4f (%.1f%%)\n",
          d, t, std::sqrt(sse / n), emax, std::sqrt(ebin2 / nb), d_fit, 100.0 * (d_fit / d - 1.0));
      std::string key = "dfit_species";
      key += std::to_string(s);
      key += "_t";
      key += std::to_string(static_cast<int>(t));
      ::testing::Test::RecordProperty(key, std::to_string(d_fit));
      // At t = 5 the D = 0.05 front (width 2 sqrt(D t) = 1) is narrower than r_cc = 1.58, below
      // the continuum limit of the model: printed, not asserted.
      if (t >= 10.0) {
        EXPECT_LT(emax, 0.05) << "D = " << d << " t = " << t;
        EXPECT_NEAR(d_fit / d, 1.0, 0.05) << "D = " << d << " t = " << t;
      }
    }
  }
}

/// Reverse Poiseuille (li2015 sec. II A): returns the measured D for one kappa.
double reverse_poiseuille_d(double kappa, int nx, int ny, double t_relax, double t_avg,
                            std::uint64_t seed) {
  Slab slab(nx, ny, {kappa}, seed);
  TdpdBackend b;
  b.initialize(slab.model, slab.state, {});
  const double dt = std::min(0.01, 0.5 * b.current_limits().diffusion);
  const double src = 0.01;  // source strength [C/time] per particle
  const double l = slab.lx;
  const int nb = nx / 2;
  std::vector<double> sum(nb, 0.0), cnt(nb, 0.0);
  ParticleState st;
  std::uint64_t step = 0;
  const double d_guess = d_of_kappa(kappa);
  {  // start near the expected steady profile to shorten the transient
    b.read_state(st);
    std::vector<double> c(st.size());
    for (std::size_t i = 0; i < st.size(); ++i) {
      const double x = st.positions[3 * i];
      const double xh = x < 0.5 * l ? x : x - 0.5 * l;
      const double sgn = x < 0.5 * l ? 1.0 : -1.0;
      c[i] = sgn * src / (2.0 * d_guess) * xh * (0.5 * l - xh);
    }
    b.set_concentrations(0, c);
  }
  while (b.time() < t_relax + t_avg) {
    b.advance(step++, dt);
    b.read_state(st);
    std::vector<double> c = b.concentrations(0);
    for (std::size_t i = 0; i < st.size(); ++i)
      c[i] += (st.positions[3 * i] < 0.5 * l ? src : -src) * dt;
    b.set_concentrations(0, c);
    if (b.time() > t_relax && step % 10 == 0) {
      for (std::size_t i = 0; i < st.size(); ++i) {
        const int k = std::min(nb - 1, static_cast<int>(st.positions[3 * i] / l * nb));
        sum[k] += c[i];
        cnt[k] += 1;
      }
    }
  }
  // Least-squares parabola C = p0 + p1 x + p2 x^2 in each half; D = src / (2 |p2|).
  double dsum = 0;
  for (int half = 0; half < 2; ++half) {
    double m[3][4] = {};
    for (int k = half * nb / 2; k < (half + 1) * nb / 2; ++k) {
      const double x = (k + 0.5) * l / nb - half * 0.5 * l;
      const double y = sum[k] / cnt[k];
      const double p[3] = {1.0, x, x * x};
      for (int r = 0; r < 3; ++r) {
        for (int q = 0; q < 3; ++q) m[r][q] += p[r] * p[q];
        m[r][3] += p[r] * y;
      }
    }
    for (int r = 0; r < 3; ++r) {  // Gauss-Jordan
      for (int q = 0; q < 3; ++q) {
        if (q == r) continue;
        const double f = m[q][r] / m[r][r];
        for (int k = 0; k < 4; ++k) m[q][k] -= f * m[r][k];
      }
    }
    dsum += src / (2.0 * std::abs(m[2][3] / m[2][2]));
  }
  return 0.5 * dsum;
}

TEST(TdpdValidation, DiffusivityOfKappaByReversePoiseuille) {
  // Reduced box (16 x 6 x 6 cells, 10 x 3.8 x 3.8) and averaging time: the cheap version.
  for (const double kappa : {0.62, 2.0, 5.0}) {
    const double d = reverse_poiseuille_d(kappa, 16, 6, 30.0, 60.0, 77);
    const double expect = d_of_kappa(kappa);
    std::printf("reverse Poiseuille kappa=%.2f: D = %.4f, li2015 fit %.4f (%.1f%%)\n", kappa, d,
                expect, 100.0 * (d / expect - 1.0));
    std::string key = "D_kappa_";
    key += std::to_string(kappa);
    ::testing::Test::RecordProperty(key, std::to_string(d));
    EXPECT_NEAR(d / expect, 1.0, 0.05) << "kappa = " << kappa;
  }
}

}  // namespace
}  // namespace sadr::fluid
