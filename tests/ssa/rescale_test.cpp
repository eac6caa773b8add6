// SPDX-License-Identifier: MIT
// update_graph() on a solver that already has a queue rescales the pending event
// times to the new rates (Gibson-Bruck) instead of drawing new ones. Checked here
// against an exact law whose rate changes between coupling steps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "sadr/ssa/nsm_solver.hpp"
#include "ssa_test_support.hpp"

namespace sadr::ssa {
namespace {

using testing::Moments;

Model birth_model(double b) {
  Model m;
  m.species = {{"A", 0}};
  m.reactions = {{"birth", {}, {{0, 1}}, b, {}, {}}};
  m.box = testing::make_box(1, 1.0, false);
  m.smoothing_length = 0.5;
  return m;
}

// Pure birth 0 -> A, b = 10 per unit volume and time, in one voxel whose volume
// V = m / rho is 1 for steps 1-25, 4 for steps 26-50 and 1 again for 51-75
// (tau = 0.02: a rebuild every 0.2-0.8 expected events, so most pending draws
// outlive a rate change). Exact: X(t_k) ~ Poisson(b sum_{l <= k} V_l tau).
// Without rescaling (old times kept) the first checkpoint after each switch is off
// by ~3 events (mean deficit (1/10 - 1/40) 40 after the 1 -> 4 switch), z ~ 40.
// Comparison points: 6 checkpoints x (mean, variance) = 12; family-wise false-failure
// rate 1e-4 (Bonferroni); R = 4000 realizations.
TEST(Rescale, BirthRateChangingWithTheVoxelVolumeGivesPoissonCounts) {
  const double b = 10, tau = 0.02;
  const std::vector<int> checkpoints = {25, 26, 30, 50, 51, 75};
  const int r_count = 4000;
  const double zs = testing::z_star(1e-4, 12);
  std::vector<Moments> mom(checkpoints.size());
  auto volume_of_step = [](int k) { return k > 25 && k <= 50 ? 4.0 : 1.0; };
  std::uint64_t rescaled_builds = 0;
  for (int r = 0; r < r_count; ++r) {
    NsmSolver s(birth_model(b), rng::mix_seed(99, static_cast<std::uint64_t>(r)));
    ParticleState p = testing::make_lattice(1, 1, 1.0);  // m = 1
    std::size_t c = 0;
    for (int k = 1; k <= 75; ++k) {
      p.densities[0] = 1.0 / volume_of_step(k);
      rescaled_builds += s.update_graph(p) && k > 1 ? 1 : 0;
      s.advance(k * tau);
      if (c < checkpoints.size() && k == checkpoints[c]) {
        mom[c++].add(static_cast<double>(s.counts(0)[0]));
      }
    }
  }
  // The density changes at steps 26 and 51 only; the other calls see equal inputs.
  EXPECT_EQ(rescaled_builds, 2u * r_count);
  double worst = 0;
  for (std::size_t c = 0; c < checkpoints.size(); ++c) {
    double lam = 0;
    for (int k = 1; k <= checkpoints[c]; ++k) lam += b * volume_of_step(k) * tau;
    const double mu4 = lam + 3 * lam * lam;  // Poisson 4th central moment
    const double z_mean = (mom[c].mean() - lam) / std::sqrt(lam / r_count);
    const double z_var = testing::variance_z(mom[c].var(), lam, mu4, r_count);
    EXPECT_LE(std::abs(z_mean), zs) << "step " << checkpoints[c] << " mean " << mom[c].mean();
    EXPECT_LE(std::abs(z_var), zs) << "step " << checkpoints[c] << " var " << mom[c].var();
    worst = std::max({worst, std::abs(z_mean), std::abs(z_var)});
  }
  RecordProperty("max_abs_z", std::to_string(worst));
}

// Diffusion on a moving graph: two voxels whose distance alternates between 0.3 h
// and 0.8 h every step (jump rate k(t) switching by ~12x). Each of the N molecules
// then sits in voxel 0 with probability p(t) = 1/2 + 1/2 exp(-2 int_0^t k), independently,
// so X_0(t) ~ Bin(N, p(t)) exactly; k per step is read from the rebuilt graph.
// Comparison points: 5 checkpoints x (mean, variance) = 10; family-wise 1e-4; R = 4000.
TEST(Rescale, TwoVoxelDiffusionOnAMovingGraphGivesTheBinomialLaw) {
  const double h = 1.0, tau = 0.05;
  Model m = testing::diffusion_model(testing::make_box(1, 4.0, false), h, 1.0);
  const std::vector<int> checkpoints = {1, 2, 5, 10, 21};
  const std::int64_t n_mol = 20;
  const int r_count = 4000;
  const double zs = testing::z_star(1e-4, 10);
  auto gap_of_step = [](int k) { return k % 2 == 1 ? 0.3 : 0.8; };
  // kappa such that the near position gives k tau = 0.5 (read from a graph at 0.3 h).
  ParticleState p = testing::make_lattice(1, 2, 1.0);
  p.positions[0] = 1.0;
  p.positions[3] = 1.0 + 0.3 * h;
  const double w_near = DiffusionGraph::build(m, p).edges[0].weight;
  m.species[0].def.diffusivity = 0.5 / (tau * w_near);
  std::vector<double> k_of_step(22, 0.0);
  std::vector<Moments> mom(checkpoints.size());
  for (int r = 0; r < r_count; ++r) {
    NsmSolver s(m, rng::mix_seed(31, static_cast<std::uint64_t>(r)));
    std::size_t c = 0;
    for (int k = 1; k <= 21; ++k) {
      p.positions[3] = 1.0 + gap_of_step(k) * h;
      s.update_graph(p);
      if (k == 1) s.set_counts(0, std::vector<std::int64_t>{n_mol, 0});
      if (r == 0) {
        const DiffusionGraph& g = s.graph();
        ASSERT_EQ(g.edge_count(), 2u);
        // Copies: Edge is packed to 12 bytes, so its weight may sit misaligned.
        const double w01 = g.edges[0].weight, w10 = g.edges[1].weight;
        ASSERT_EQ(w01, w10);  // equal masses and densities
        k_of_step[k] = m.species[0].def.diffusivity * w01;
      }
      s.advance(k * tau);
      if (c < checkpoints.size() && k == checkpoints[c]) {
        mom[c++].add(static_cast<double>(s.counts(0)[0]));
      }
    }
  }
  double worst = 0, integral = 0;
  std::size_t c = 0;
  for (int k = 1; k <= 21 && c < checkpoints.size(); ++k) {
    integral += k_of_step[k] * tau;
    if (k != checkpoints[c]) continue;
    const double prob = 0.5 + 0.5 * std::exp(-2.0 * integral);
    const double mean = n_mol * prob, var = n_mol * prob * (1 - prob);
    const double z_mean = (mom[c].mean() - mean) / std::sqrt(var / r_count);
    const double z_var =
        testing::variance_z(mom[c].var(), var, testing::binomial_mu4(n_mol, prob), r_count);
    EXPECT_LE(std::abs(z_mean), zs) << "step " << k << " mean " << mom[c].mean() << " vs " << mean;
    EXPECT_LE(std::abs(z_var), zs) << "step " << k << " var " << mom[c].var() << " vs " << var;
    worst = std::max({worst, std::abs(z_mean), std::abs(z_var)});
    ++c;
  }
  EXPECT_EQ(c, checkpoints.size());
  RecordProperty("max_abs_z", std::to_string(worst));
}

// A voxel with molecules but no neighbour has rate 0 (time +inf); once a particle
// comes within h it gets a fresh draw (rescaling needs a finite old time).
TEST(Rescale, IdleVoxelGetsAFreshDrawWhenItGainsNeighbours) {
  Model m;
  m.species = {{"A", 1.0}};
  m.box = testing::make_box(1, 10.0, false);
  m.smoothing_length = 1.0;
  ParticleState p = testing::make_lattice(1, 2, 1.0);  // x = 0.5 and 1.5: neighbours
  p.positions[3 * 1] = 5.0;                            // moved away: no edge
  NsmSolver s(m, 5);
  s.update_graph(p);
  s.set_counts(0, std::vector<std::int64_t>{10, 0});
  EXPECT_EQ(s.voxel_rate(0), 0.0);
  EXPECT_TRUE(std::isinf(s.queue().time_of(0)));
  s.advance(1.0);
  EXPECT_EQ(s.counts(0)[0], 10);
  p.positions[3 * 1] = 1.2;  // back within h
  ASSERT_TRUE(s.update_graph(p));
  EXPECT_GT(s.voxel_rate(0), 0.0);
  EXPECT_TRUE(std::isfinite(s.queue().time_of(0)));
  EXPECT_GT(s.queue().time_of(0), 1.0);
  s.advance(1000.0);
  EXPECT_EQ(s.counts(0)[0] + s.counts(0)[1], 10);
  EXPECT_GT(s.counts(0)[1], 0);
}

// Rescaling keeps the law when only the graph changes: a restored solver rescales
// the same way (its cached rates are recomputed from the same counts).
TEST(Rescale, RestoredSolverRescalesBitIdentically) {
  Model m;
  m.species = {{"A", 0.7}};
  m.box = testing::make_box(2, 8.0, true);
  m.smoothing_length = 2.5;
  ParticleState p = testing::make_lattice(2, 8, 1.0, 0.2, 0.2, 3);
  NsmSolver a(m, 11);
  a.update_graph(p);
  a.set_counts(0, std::vector<std::int64_t>(p.size(), 3));
  a.advance(0.5);
  const std::string blob = a.save();
  NsmSolver b(m, 999);
  b.restore(blob);
  for (int k = 1; k <= 5; ++k) {
    for (std::size_t i = 0; i < p.size(); ++i) p.positions[3 * i] += 0.01 * ((i * 7 + k) % 5);
    a.update_graph(p);
    b.update_graph(p);
    a.advance(0.5 + 0.2 * k);
    b.advance(0.5 + 0.2 * k);
    ASSERT_EQ(a.events(), b.events()) << "step " << k;
    ASSERT_TRUE(std::equal(a.counts(0).begin(), a.counts(0).end(), b.counts(0).begin()));
    for (std::size_t i = 0; i < p.size(); ++i) {
      ASSERT_EQ(a.queue().time_of(static_cast<std::uint32_t>(i)),
                b.queue().time_of(static_cast<std::uint32_t>(i)));
    }
  }
}

}  // namespace
}  // namespace sadr::ssa
