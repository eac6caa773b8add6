// SPDX-License-Identifier: MIT
// Free walls (cell membranes): molecules cross a free wall voxel like a fluid voxel, pure
// diffusion reaches the uniform equilibrium including the free wall, and wall-kind
// reactions fire on the free wall only (molecules cannot reach a no-flux wall).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "sadr/ssa/nsm_solver.hpp"
#include "ssa_test_support.hpp"

namespace sadr::ssa {
namespace {

// 1D chain of 8 (dx = 1, h = 1.5: nearest neighbours, hop rate 1), walls at 0 (free for A)
// and 7 (no-flux). The open voxels 0..6 form a path of 7: X ~ Multinomial(40, 1/7) at
// equilibrium. From 40 molecules at voxel 3, the slowest mode 2(1 - cos(pi/7)) = 0.198
// leaves a bias <= 40 e^{-0.198 * 60} < 1e-4 at T = 60. Mean test with the exact multinomial
// variance; M = 7 voxels; alpha_fw = 1e-4; R = 1000.
TEST(FreeWalls, ChainWithFreeWallConservesAndReachesUniformEquilibrium) {
  const double h = 1.5;
  const double kappa = 1.0 / (2.0 * lucy_f(1.0, h, 1) / (1.0 + 0.01 * h * h));
  Model m = testing::diffusion_model(testing::make_box(1, 8.0, false), h, kappa);
  m.free_walls = {{0, {0}}};
  ParticleState p = testing::make_lattice(1, 8, 1.0);
  p.kinds[0] = p.kinds[7] = ParticleKind::kWall;
  const int r_count = 1000;
  std::vector<testing::Moments> mom(7);
  for (int r = 0; r < r_count; ++r) {
    NsmSolver s(m, rng::mix_seed(8080, static_cast<std::uint64_t>(r)));
    s.update_graph(p);
    s.set_counts(0, std::vector<std::int64_t>{0, 0, 0, 40, 0, 0, 0, 0});
    for (int k = 1; k <= 4; ++k) {
      s.advance(15.0 * k);
      std::int64_t total = 0;
      for (auto x : s.counts(0)) total += x;
      ASSERT_EQ(total, 40);
      ASSERT_EQ(s.counts(0)[7], 0);
    }
    for (int i = 0; i < 7; ++i) mom[i].add(static_cast<double>(s.counts(0)[i]));
  }
  const double zs = testing::z_star(1e-4, 7);
  const double pi = 1.0 / 7.0, mean = 40 * pi, var = 40 * pi * (1 - pi);
  for (int i = 0; i < 7; ++i) {
    EXPECT_LE(std::abs(mom[i].mean() - mean) / std::sqrt(var / r_count), zs)
        << "voxel " << i << " mean " << mom[i].mean() << " vs " << mean;
  }
}

// A -> B with kinds {kWall}; B immobile. A diffuses from the fluid; the only wall A can
// reach is the free one, so every B is made there (deterministic property, fixed seeds).
TEST(FreeWalls, WallReactionFiresOnlyOnFreeWallVoxels) {
  Model m = testing::diffusion_model(testing::make_box(2, 6.0, false), 1.5, 1.0);
  m.species.push_back({"B", 0.0});
  m.reactions = {{"uptake", {{0, 1}}, {{1, 1}}, 2.0, {ParticleKind::kWall}, {}}};
  ParticleState p = testing::make_lattice(2, 6, 1.0);
  std::vector<std::uint32_t> free;
  for (std::uint32_t i = 0; i < p.size(); ++i) {
    const double x = p.positions[3 * i], y = p.positions[3 * i + 1];
    if (x < 1.0 || x > 5.0) p.kinds[i] = ParticleKind::kWall;
    if (x < 1.0 && y > 2.0 && y < 4.0) free.push_back(i);  // two free walls on the left
  }
  m.free_walls = {{0, free}};
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    NsmSolver s(m, seed);
    s.update_graph(p);
    std::vector<std::int64_t> a(p.size(), 0);
    for (std::uint32_t i = 0; i < p.size(); ++i) {
      if (p.kinds[i] != ParticleKind::kWall) a[i] = 3;
    }
    s.set_counts(0, a);
    s.advance(20.0);
    std::int64_t made = 0, total = 0;
    for (std::uint32_t i = 0; i < p.size(); ++i) {
      const bool is_free = std::find(free.begin(), free.end(), i) != free.end();
      if (!is_free) {
        ASSERT_EQ(s.counts(1)[i], 0) << "B made in non-free voxel " << i;
      }
      if (p.kinds[i] == ParticleKind::kWall && !is_free) {
        ASSERT_EQ(s.counts(0)[i], 0);
      }
      made += s.counts(1)[i];
      total += s.counts(0)[i] + s.counts(1)[i];
    }
    EXPECT_EQ(total, 3 * 24);
    EXPECT_GT(made, 0);
  }
}

}  // namespace
}  // namespace sadr::ssa
