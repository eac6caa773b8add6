// SPDX-License-Identifier: MIT
// Dirichlet reservoir walls: a 1D chain between a wall held at 50 molecules and a wall
// held at 0 relaxes to the linear steady profile (product-Poisson stationary law).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "sadr/ssa/nsm_solver.hpp"
#include "ssa_test_support.hpp"

namespace sadr::ssa {
namespace {

// 12 particles (dx = 1, h = 1.5: nearest neighbours only, hop rate 1), walls at 0 and 11.
// Stationary mean m_i = 50 (11 - i)/11 (exact for this graph), Poisson variance.
// Started empty; at T = 100 the slowest mode (rate 2(1 - cos(pi/11)) = 0.081) leaves a
// bias <= 50 e^{-8.1} = 0.015 = tau. M = 10 voxels; alpha_fw = 1e-4; R = 300.
TEST(ReservoirWalls, ChainReachesLinearSteadyProfile) {
  const double h = 1.5;
  const double kappa = 1.0 / (2.0 * lucy_f(1.0, h, 1) / (1.0 + 0.01 * h * h));
  Model m = testing::diffusion_model(testing::make_box(1, 12.0, false), h, kappa);
  m.reservoirs = {{0, 50.0, {0}}, {0, 0.0, {11}}};
  ParticleState p = testing::make_lattice(1, 12, 1.0);
  p.kinds[0] = p.kinds[11] = ParticleKind::kWall;
  const int r_count = 300;
  const double t_end = 100.0;
  std::vector<testing::Moments> mom(12);
  for (int r = 0; r < r_count; ++r) {
    NsmSolver s(m, rng::mix_seed(555, static_cast<std::uint64_t>(r)));
    s.update_graph(p);
    ASSERT_EQ(s.counts(0)[0], 50);
    ASSERT_EQ(s.counts(0)[11], 0);
    s.advance(t_end);
    ASSERT_EQ(s.counts(0)[0], 50);  // reservoirs hold their counts
    ASSERT_EQ(s.counts(0)[11], 0);
    for (int i = 0; i < 12; ++i) mom[i].add(static_cast<double>(s.counts(0)[i]));
  }
  const double zs = testing::z_star(1e-4, 10);
  const double tau = 50.0 * std::exp(-2.0 * (1 - std::cos(M_PI / 11)) * t_end);
  for (int i = 1; i <= 10; ++i) {
    const double mean = 50.0 * (11 - i) / 11.0;
    const double se = std::sqrt(mean / r_count);
    EXPECT_LE(std::abs(mom[i].mean() - mean), tau + zs * se) << "voxel " << i;
  }
}

// A Neumann source injects flux * l^(d-1) per unit time into the first fluid layer.
TEST(NeumannSource, InjectsIntoFirstFluidLayerOnly) {
  Model m = testing::diffusion_model(testing::make_box(2, 6.0, false), 1.5, 0.0);
  m.neumann = {{0, 3.0}};
  ParticleState p = testing::make_lattice(2, 6, 1.0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.positions[3 * i] < 1.0) p.kinds[i] = ParticleKind::kWall;
  }
  NsmSolver s(m, 3);
  s.update_graph(p);
  for (std::uint32_t i = 0; i < p.size(); ++i) {
    const double x = p.positions[3 * i];
    const double expect = (x > 1.0 && x < 2.0) ? 3.0 * 1.0 : 0.0;  // l = 1 in 2D: flux * l
    EXPECT_DOUBLE_EQ(s.voxel_rate(i), expect) << "particle " << i << " x=" << x;
  }
}

}  // namespace
}  // namespace sadr::ssa
