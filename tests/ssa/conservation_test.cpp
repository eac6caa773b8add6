// SPDX-License-Identifier: MIT
// Pure diffusion conserves molecules and never goes negative; each jump convention
// reaches the equilibrium it promises (docs/method.md section 4).
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <vector>

#include "sadr/ssa/nsm_solver.hpp"
#include "ssa_test_support.hpp"

namespace sadr::ssa {
namespace {

TEST(Conservation, PureDiffusionConservesMoleculesWithNoFluxWalls) {
  Model m = testing::diffusion_model(testing::make_box(3, 6.0, false), 1.8, 0.7);
  m.species.push_back({"B", 0.0});  // immobile: no diffusion bookkeeping, never moves
  ParticleState p = testing::make_lattice(3, 6, 1.0, 0.25, 0.3, 8);
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.positions[3 * i + 2] < 1.0) p.kinds[i] = ParticleKind::kWall;
  }
  NsmSolver s(m, 4242);
  s.update_graph(p);
  std::vector<std::int64_t> x(p.size(), 0), y(p.size(), 0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kinds[i] != ParticleKind::kWall) x[i] = static_cast<std::int64_t>(i % 7);
    y[i] = static_cast<std::int64_t>(i % 3);
  }
  const std::int64_t total = std::accumulate(x.begin(), x.end(), std::int64_t{0});
  s.set_counts(0, x);
  s.set_counts(1, y);
  for (int step = 1; step <= 20; ++step) {
    s.advance(0.5 * step);
    const auto c = s.counts(0);
    EXPECT_EQ(std::accumulate(c.begin(), c.end(), std::int64_t{0}), total);
    for (std::size_t i = 0; i < p.size(); ++i) {
      ASSERT_GE(c[i], 0);
      if (p.kinds[i] == ParticleKind::kWall) {
        ASSERT_EQ(c[i], 0) << "molecule entered a wall";
      }
      ASSERT_EQ(s.counts(1)[i], y[i]);
    }
  }
  EXPECT_GT(s.events(), 10000u);
}

// Closed 1D chain of 8 particles with volumes V_i varying by up to +-40 %.
// 'volume' promises uniform concentration (pi_i ~ V_i), 'symmetric' equal counts.
// At T = 80 (>= 20 relaxation times) X ~ Multinomial(40, pi): mean test with the exact
// multinomial variance; M = 2 conventions x 8 voxels = 16; alpha_fw = 1e-4; R = 1000.
TEST(Equilibrium, EachConventionReachesItsPromisedEquilibrium) {
  const double zs = testing::z_star(1e-4, 16);
  const ParticleState p = testing::make_lattice(1, 8, 1.0, 0.0, 0.4, 21);
  for (auto conv : {JumpConvention::kVolume, JumpConvention::kSymmetric}) {
    Model m = testing::diffusion_model(testing::make_box(1, 8.0, false), 1.5, 1.0, conv);
    double vsum = 0;
    for (std::size_t i = 0; i < 8; ++i) vsum += p.masses[i] / p.densities[i];
    std::vector<testing::Moments> mom(8);
    const int r_count = 1000;
    for (int r = 0; r < r_count; ++r) {
      NsmSolver s(m, rng::mix_seed(60 + static_cast<int>(conv), static_cast<std::uint64_t>(r)));
      s.update_graph(p);
      s.set_counts(0, std::vector<std::int64_t>{40, 0, 0, 0, 0, 0, 0, 0});
      s.advance(80.0);
      for (int i = 0; i < 8; ++i) mom[i].add(static_cast<double>(s.counts(0)[i]));
    }
    for (int i = 0; i < 8; ++i) {
      const double pi =
          conv == JumpConvention::kVolume ? p.masses[i] / p.densities[i] / vsum : 1.0 / 8.0;
      const double mean = 40 * pi, var = 40 * pi * (1 - pi);
      EXPECT_LE(std::abs(mom[i].mean() - mean) / std::sqrt(var / r_count), zs)
          << to_string(conv) << " voxel " << i << " mean " << mom[i].mean() << " vs " << mean;
    }
  }
}

}  // namespace
}  // namespace sadr::ssa
