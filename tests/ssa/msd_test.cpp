// SPDX-License-Identifier: MIT
// Point release, pure diffusion: the mean-square displacement grows as
// 2 d kappa_eff t with kappa_eff = ratio * kappa from refs/sph_consistency.csv.
//
// Regular periodic lattice: exact in expectation (translation invariance gives
// d/dt E[r^2] = sum_j d_0j r_j^2 = 2 d kappa ratio), so tau = 0 and only the
// statistical error counts. Irregular sets (jittered lattice): the disordered SPH
// operator has its own consistency error, so an equivalence margin tau is stated.
// Statistics: molecules are independent walkers, SE = sd(r^2)/sqrt(N0) from the sample;
// PASS iff |MSD - 2 d kappa_eff t| <= tau 2 d kappa_eff t + z* SE, alpha_fw = 1e-4 over
// M = 3 times per case (z* from Bonferroni).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "sadr/ssa/nsm_solver.hpp"
#include "ssa_test_support.hpp"

namespace sadr::ssa {
namespace {

struct MsdCase {
  int dim;
  int n;                       // particles per axis
  double h_over_dx;            // kernel support / spacing
  double jitter;               // 0 = regular lattice
  double tau;                  // modelling margin (relative)
  std::vector<double> sigmas;  // per-axis RMS displacement at the sample times [dx]
};

class MsdTest : public ::testing::TestWithParam<MsdCase> {};

TEST_P(MsdTest, GrowsAsTwoDKappaEffT) {
  const MsdCase c = GetParam();
  const double dx = 1.0, kappa = 1.0;
  const double len = c.n * dx;
  const double ratio = testing::kappa_ratio(c.dim, 0.01, c.h_over_dx);
  const double kappa_eff = ratio * kappa;
  Model m = testing::diffusion_model(testing::make_box(c.dim, len, true), c.h_over_dx * dx, kappa);
  const ParticleState p = testing::make_lattice(c.dim, c.n, dx, c.jitter, 0.0, 17);
  NsmSolver s(m, rng::mix_seed(31, static_cast<std::uint64_t>(c.dim * 10 + (c.jitter > 0))));
  s.update_graph(p);
  // Release at the particle nearest the box centre.
  std::size_t src = 0;
  double best = 1e300;
  for (std::size_t i = 0; i < p.size(); ++i) {
    double r2 = 0;
    for (int a = 0; a < c.dim; ++a) r2 += std::pow(p.positions[3 * i + a] - 0.5 * len, 2);
    if (r2 < best) best = r2, src = i;
  }
  const std::int64_t n0 = 100000;
  std::vector<std::int64_t> x(p.size(), 0);
  x[src] = n0;
  s.set_counts(0, x);
  const double zs = testing::z_star(1e-4, 3);
  for (double sigma : c.sigmas) {
    const double t = sigma * sigma / (2 * kappa_eff);
    s.advance(t);
    double m2 = 0, m4 = 0;
    std::int64_t total = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const auto xi = s.counts(0)[i];
      if (xi == 0) continue;
      double r2 = 0;
      for (int a = 0; a < c.dim; ++a) {
        double d = p.positions[3 * i + a] - p.positions[3 * src + a];
        d -= len * std::round(d / len);
        r2 += d * d;
      }
      m2 += xi * r2, m4 += xi * r2 * r2, total += xi;
    }
    ASSERT_EQ(total, n0);
    const double msd = m2 / n0;
    const double se = std::sqrt((m4 / n0 - msd * msd) / n0);
    const double expect = 2 * c.dim * kappa_eff * t;
    const double allowed = c.tau * expect + zs * se;
    EXPECT_LE(std::abs(msd - expect), allowed)
        << "d=" << c.dim << " jitter=" << c.jitter << " t=" << t << " msd/expect=" << msd / expect
        << " (relative SE " << se / expect << ")";
    std::printf("MSD d=%d jitter=%.2f t=%.4g msd/expect=%.5f rel.SE=%.5f\n", c.dim, c.jitter, t,
                msd / expect, se / expect);
    RecordProperty("msd_over_expect_t" + std::to_string(t), std::to_string(msd / expect));
  }
}

// Irregular margin tau = 4 %: the measured MSD/expected on these jittered sets is within
// 1-2 % (docs/ssa-core.md); the margin is the disordered-particle consistency error,
// not statistics.
INSTANTIATE_TEST_SUITE_P(RegularAndIrregular, MsdTest,
                         ::testing::Values(MsdCase{1, 400, 3.0, 0.0, 0.0, {2.0, 4.0, 6.0}},
                                           MsdCase{2, 48, 3.0, 0.0, 0.0, {1.5, 3.0, 4.5}},
                                           MsdCase{3, 20, 3.0, 0.0, 0.0, {1.0, 2.0, 2.5}},
                                           MsdCase{1, 400, 3.0, 0.2, 0.04, {2.0, 4.0, 6.0}},
                                           MsdCase{2, 48, 3.0, 0.2, 0.04, {1.5, 3.0, 4.5}},
                                           MsdCase{3, 20, 3.0, 0.2, 0.04, {1.0, 2.0, 2.5}}));

}  // namespace
}  // namespace sadr::ssa
