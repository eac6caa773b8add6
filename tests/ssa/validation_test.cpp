// SPDX-License-Identifier: MIT
// Long ensembles (label validation, opt-in): the property tests with 10-20x more
// realizations, and an independent cross-check of our graph dump against
// tests/ssa/linear_rdme_reference.py (python3 + scipy, which deploy/install-deps.sh installs).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "linear_exact.hpp"
#include "sadr/ssa/graph_json.hpp"
#include "sadr/ssa/nsm_solver.hpp"
#include "ssa_test_support.hpp"

namespace sadr::ssa {
namespace {

using testing::Moments;

Model irregular_model() {
  Model m = testing::diffusion_model(testing::make_box(2, 5.0, false), 1.7, 0.3);
  m.reactions = {{"decay", {{0, 1}}, {}, 0.2, {}, {}}, {"birth", {}, {{0, 1}}, 2.0, {}, {}}};
  return m;
}

// The exact mean and variance of tests/ssa/linear_rdme_reference.py (scipy expm_multiply, an
// implementation independent of linear_exact.hpp) on OUR dumped graph equal the Eigen expm
// solution used by the property tests (relative 1e-9): validates the JSON dump and the C++
// exact solution against each other. Deterministic.
TEST(Validation, DumpedGraphMatchesScipyReference) {
  ASSERT_EQ(std::system("/usr/bin/python3 -c 'import scipy' > /dev/null 2>&1"), 0)
      << "needs /usr/bin/python3 with scipy (deploy/install-deps.sh installs python3-scipy)";
  NsmSolver s(irregular_model(), 1);
  const ParticleState p = testing::make_lattice(2, 5, 1.0, 0.3, 0.3, 11);
  s.update_graph(p);
  LinearRdmeSpec spec;
  spec.kappa = 0.3;
  spec.decay = 0.2;
  for (std::size_t i = 0; i < 25; ++i) spec.birth.push_back(2.0 * s.graph().volume[i]);
  spec.x0.assign(25, 0);
  spec.x0[12] = 200;
  spec.times = {0.5, 2.0, 8.0};
  spec.variance = true;
  const std::string dir = SADR_BINARY_DIR;
  const std::string json = dir + "/ssa_irregular25.json", csv = dir + "/ssa_irregular25_mean.csv";
  std::ofstream(json) << graph_to_json(s.graph(), spec);
  const std::string cmd = std::string("/usr/bin/python3 ") + SADR_SOURCE_DIR +
                          "/tests/ssa/linear_rdme_reference.py " + json + " --out " + csv;
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  std::vector<double> b(spec.birth), x0(25, 0.0);
  x0[12] = 200;
  int compared = 0;
  for (const auto& row : testing::read_csv(csv)) {
    const double t = std::stod(row.at("t"));
    const int i = std::stoi(row.at("voxel"));
    const auto ex = testing::linear_exact(s.graph(), 0.3, 0.2, b, x0, t);
    EXPECT_NEAR(std::stod(row.at("mean")), ex.mean(i), 1e-9 * std::max(1.0, ex.mean(i)));
    EXPECT_NEAR(std::stod(row.at("var")), ex.var(i), 1e-9 * std::max(1.0, ex.var(i)));
    ++compared;
  }
  EXPECT_EQ(compared, 75);
}

// Irregular first-order network with R = 20000 (10x the property test): mean and
// variance of 25 voxels at 3 times, M = 150, alpha_fw = 1e-4.
TEST(Validation, IrregularNetworkLargeEnsemble) {
  const Model m = irregular_model();
  const ParticleState p = testing::make_lattice(2, 5, 1.0, 0.3, 0.3, 11);
  const std::vector<double> times = {0.5, 2, 8};
  const int r_count = 20000;
  std::vector<std::vector<Moments>> mom(times.size(), std::vector<Moments>(25));
  DiffusionGraph graph;
  for (int r = 0; r < r_count; ++r) {
    NsmSolver s(m, rng::mix_seed(8080, static_cast<std::uint64_t>(r)));
    s.update_graph(p);
    if (r == 0) graph = s.graph();
    std::vector<std::int64_t> init(25, 0);
    init[12] = 200;
    s.set_counts(0, init);
    for (std::size_t t = 0; t < times.size(); ++t) {
      s.advance(times[t]);
      for (int i = 0; i < 25; ++i) mom[t][i].add(static_cast<double>(s.counts(0)[i]));
    }
  }
  std::vector<double> b(25), x0(25, 0.0);
  for (int i = 0; i < 25; ++i) b[i] = 2.0 * graph.volume[i];
  x0[12] = 200;
  const double zs = testing::z_star(1e-4, 150);
  double worst = 0;
  for (std::size_t t = 0; t < times.size(); ++t) {
    const auto ex = testing::linear_exact(graph, 0.3, 0.2, b, x0, times[t]);
    for (int i = 0; i < 25; ++i) {
      const double pj = ex.p(i, 12), lam = ex.lambda(i), var = ex.var(i);
      const double mu4 =
          testing::binomial_mu4(200, pj) + lam + 3 * lam * lam + 6 * 200 * pj * (1 - pj) * lam;
      const double zm = (mom[t][i].mean() - ex.mean(i)) / std::sqrt(var / r_count);
      const double zv = testing::variance_z(mom[t][i].var(), var, mu4, r_count);
      EXPECT_LE(std::abs(zm), zs);
      EXPECT_LE(std::abs(zv), zs);
      worst = std::max({worst, std::abs(zm), std::abs(zv)});
    }
  }
  std::printf("irregular network R=%d: max |z| = %.3f (z* = %.3f)\n", r_count, worst, zs);
}

// Birth-death x0 = 0 with R = 40000: mean and variance at 7 times (M = 14,
// alpha_fw = 1e-4), i.e. a 0.5 % resolution of the mean at t = 50.
TEST(Validation, BirthDeathLargeEnsemble) {
  const std::vector<double> times = {0.5, 1, 2, 5, 10, 20, 50};
  const int r_count = 40000;
  std::vector<Moments> mom(times.size());
  Model m;
  m.species = {{"A", 0}};
  m.reactions = {{"birth", {}, {{0, 1}}, 10.0, {}, {}}, {"death", {{0, 1}}, {}, 0.1, {}, {}}};
  m.box = testing::make_box(1, 1.0, false);
  m.smoothing_length = 0.5;
  for (int r = 0; r < r_count; ++r) {
    NsmSolver s(m, rng::mix_seed(4321, static_cast<std::uint64_t>(r)));
    s.update_graph(testing::make_lattice(1, 1, 1.0));
    for (std::size_t t = 0; t < times.size(); ++t) {
      s.advance(times[t]);
      mom[t].add(static_cast<double>(s.counts(0)[0]));
    }
  }
  const double zs = testing::z_star(1e-4, 14);
  for (std::size_t t = 0; t < times.size(); ++t) {
    const double lam = 100.0 * (1 - std::exp(-0.1 * times[t]));
    const double zm = (mom[t].mean() - lam) / std::sqrt(lam / r_count);
    const double zv = testing::variance_z(mom[t].var(), lam, lam + 3 * lam * lam, r_count);
    EXPECT_LE(std::abs(zm), zs) << "t=" << times[t];
    EXPECT_LE(std::abs(zv), zs) << "t=" << times[t];
  }
}

}  // namespace
}  // namespace sadr::ssa
