// SPDX-License-Identifier: MIT
// First-order RDME networks on fixed graphs: NSM ensemble mean (and variance) of
// every voxel against the exact solution dm/dt = M m + s (refs/README.md section 6).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "linear_exact.hpp"
#include "sadr/ssa/nsm_solver.hpp"
#include "ssa_test_support.hpp"

namespace sadr::ssa {
namespace {

using testing::Moments;

// refs case 6a (lattice20): 20 voxels on a line, hop rate 1 per molecule to each nearest
// neighbour, reflecting ends, A -> 0 at 0.1, 0 -> A at 5 per voxel, 1000 molecules in voxel 0.
// Built from particles (dx = 1, h = 1.5 dx, V = 1) with kappa chosen so d_ij = 1 exactly,
// compared with the shipped exact CSV rdme_linear_mean_lattice20.csv (mean, var).
// M = 20 voxels x 6 times = 120 mean tests with the exact variance; alpha_fw = 1e-4; R = 1000.
TEST(LinearNetwork, Lattice20MatchesShippedExactMean) {
  const double h = 1.5;
  const double reg = 1.0 / (1.0 + 0.01 * h * h);
  const double kappa = 1.0 / (2.0 * lucy_f(1.0, h, 1) * reg);
  Model m = testing::diffusion_model(testing::make_box(1, 20.0, false), h, kappa);
  m.reactions = {{"decay", {{0, 1}}, {}, 0.1, {}, {}}, {"birth", {}, {{0, 1}}, 5.0, {}, {}}};
  const ParticleState p = testing::make_lattice(1, 20, 1.0);
  const std::vector<double> times = {0.5, 1, 2, 5, 10, 20};
  const int r_count = 1000;
  std::vector<std::vector<Moments>> mom(times.size(), std::vector<Moments>(20));
  for (int r = 0; r < r_count; ++r) {
    NsmSolver s(m, rng::mix_seed(2024, static_cast<std::uint64_t>(r)));
    s.update_graph(p);
    std::vector<std::int64_t> x0(20, 0);
    x0[0] = 1000;
    s.set_counts(0, x0);
    for (std::size_t t = 0; t < times.size(); ++t) {
      s.advance(times[t]);
      for (int i = 0; i < 20; ++i) mom[t][i].add(static_cast<double>(s.counts(0)[i]));
    }
    if (r == 0) {  // the graph really is the unit-rate chain
      const auto& g = s.graph();
      ASSERT_EQ(g.edge_count(), 38u);
      for (const auto& e : g.edges) ASSERT_NEAR(kappa * e.weight, 1.0, 1e-14);
    }
  }
  const double zs = testing::z_star(1e-4, 120);
  int compared = 0;
  double worst = 0;
  for (const auto& row : testing::read_csv(testing::refs_path("rdme_linear_mean_lattice20.csv"))) {
    if (row.at("t") == "inf") continue;
    const double t = std::stod(row.at("t"));
    const auto it = std::find(times.begin(), times.end(), t);
    if (it == times.end()) continue;
    const int i = std::stoi(row.at("voxel"));
    const auto& mo = mom[it - times.begin()][i];
    const double z =
        (mo.mean() - std::stod(row.at("mean"))) / std::sqrt(std::stod(row.at("var")) / r_count);
    EXPECT_LE(std::abs(z), zs) << "t=" << t << " voxel " << i;
    worst = std::max(worst, std::abs(z));
    ++compared;
  }
  EXPECT_EQ(compared, 120);
  RecordProperty("max_abs_z", std::to_string(worst));
}

// Irregular 2D particle set (jittered 5x5 lattice, masses +-30 %, walled box), 'volume'
// convention, kappa = 0.3, A -> 0 at 0.2, 0 -> A at 2 per unit volume (b_i = 2 V_i),
// 200 molecules released in voxel 12. Exact mean/variance/4th moment from expm in C++.
// M = 25 voxels x 3 times x (mean + variance) = 150 tests; alpha_fw = 1e-4; R = 2000.
TEST(LinearNetwork, IrregularGraphMeanAndVarianceMatchExpm) {
  Model m = testing::diffusion_model(testing::make_box(2, 5.0, false), 1.7, 0.3);
  m.reactions = {{"decay", {{0, 1}}, {}, 0.2, {}, {}}, {"birth", {}, {{0, 1}}, 2.0, {}, {}}};
  const ParticleState p = testing::make_lattice(2, 5, 1.0, 0.3, 0.3, 11);
  const std::vector<double> times = {0.5, 2, 8};
  const int r_count = 2000;
  const std::uint32_t src = 12;
  const std::int64_t x0 = 200;
  std::vector<std::vector<Moments>> mom(times.size(), std::vector<Moments>(25));
  DiffusionGraph graph;
  for (int r = 0; r < r_count; ++r) {
    NsmSolver s(m, rng::mix_seed(77, static_cast<std::uint64_t>(r)));
    s.update_graph(p);
    if (r == 0) graph = s.graph();
    std::vector<std::int64_t> init(25, 0);
    init[src] = x0;
    s.set_counts(0, init);
    for (std::size_t t = 0; t < times.size(); ++t) {
      s.advance(times[t]);
      for (int i = 0; i < 25; ++i) mom[t][i].add(static_cast<double>(s.counts(0)[i]));
    }
  }
  ASSERT_GT(graph.edge_count(), 100u);  // genuinely irregular: many unequal edges
  std::vector<double> b(25), xinit(25, 0.0);
  for (int i = 0; i < 25; ++i) b[i] = 2.0 * graph.volume[i];
  xinit[src] = static_cast<double>(x0);
  const double zs = testing::z_star(1e-4, 150);
  double worst = 0;
  for (std::size_t t = 0; t < times.size(); ++t) {
    const auto ex = testing::linear_exact(graph, 0.3, 0.2, b, xinit, times[t]);
    for (int i = 0; i < 25; ++i) {
      const double pj = ex.p(i, src), lam = ex.lambda(i), var = ex.var(i);
      const double vb = x0 * pj * (1 - pj);
      const double mu4 =
          testing::binomial_mu4(static_cast<double>(x0), pj) + lam + 3 * lam * lam + 6 * vb * lam;
      const double z_mean = (mom[t][i].mean() - ex.mean(i)) / std::sqrt(var / r_count);
      const double z_var = testing::variance_z(mom[t][i].var(), var, mu4, r_count);
      EXPECT_LE(std::abs(z_mean), zs) << "t=" << times[t] << " voxel " << i;
      EXPECT_LE(std::abs(z_var), zs) << "t=" << times[t] << " voxel " << i;
      worst = std::max({worst, std::abs(z_mean), std::abs(z_var)});
    }
  }
  RecordProperty("max_abs_z", std::to_string(worst));
}

}  // namespace
}  // namespace sadr::ssa
