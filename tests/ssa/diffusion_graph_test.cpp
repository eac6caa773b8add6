// SPDX-License-Identifier: MIT
// Edge weights of the particle diffusion graph (docs/method.md section 4).
#include "sadr/ssa/diffusion_graph.hpp"

#include <gtest/gtest.h>
#include <algorithm>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include "sadr/ssa/neighbor_list.hpp"

#include <cmath>
#include <map>
#include <numbers>

#include "sadr/ssa/graph_json.hpp"
#include "ssa_test_support.hpp"

namespace sadr::ssa {
namespace {

double weight(const DiffusionGraph& g, std::uint32_t i, std::uint32_t j) {
  for (auto k = g.row_start[i]; k < g.row_start[i + 1]; ++k) {
    if (g.edges[k].target == j) return g.edges[k].weight;
  }
  return 0;
}

TEST(LucyKernel, RadialFactorMatchesDerivativeOfW) {
  // F = -(1/r) dW/dr; check by central differences of W in 1D/2D/3D.
  const double h = 1.3;
  for (int d = 1; d <= 3; ++d) {
    const double alpha = d == 1   ? 5.0 / (4 * h)
                         : d == 2 ? 5.0 / (std::numbers::pi * h * h)
                                  : 105.0 / (16 * std::numbers::pi * h * h * h);
    auto w = [&](double r) {
      const double q = r / h;
      return q < 1 ? alpha * (1 + 3 * q) * std::pow(1 - q, 3) : 0.0;
    };
    for (double r : {0.1, 0.5, 0.9, 1.2}) {
      const double e = 1e-6;
      const double dwdr = (w(r + e) - w(r - e)) / (2 * e);
      EXPECT_NEAR(lucy_f(r, h, d), -dwdr / r, 1e-6 * std::abs(dwdr / r) + 1e-9) << d << " " << r;
    }
    EXPECT_EQ(lucy_f(h, h, d), 0.0);
  }
}

TEST(DiffusionGraph, SymmetricConventionIsSymmetricAndMatchesEq28) {
  ParticleState p = testing::make_lattice(2, 8, 1.0, 0.3, 0.3, 3);
  Model m = testing::diffusion_model(testing::make_box(2, 8.0, true), 2.5, 1.0,
                                     JumpConvention::kSymmetric);
  for (std::size_t i = 0; i < p.size(); ++i) p.densities[i] = 1 + 0.1 * static_cast<double>(i % 3);
  const DiffusionGraph g = DiffusionGraph::build(m, p);
  std::size_t checked = 0;
  for (std::uint32_t i = 0; i < g.size(); ++i) {
    for (auto k = g.row_start[i]; k < g.row_start[i + 1]; ++k) {
      const std::uint32_t j = g.edges[k].target;
      EXPECT_DOUBLE_EQ(g.edges[k].weight, weight(g, j, i));
      // Eq 28 recomputed from scratch with the minimum image.
      double r2 = 0;
      for (int a = 0; a < 2; ++a) {
        double dx = p.positions[3 * i + a] - p.positions[3 * j + a];
        dx -= 8.0 * std::round(dx / 8.0);
        r2 += dx * dx;
      }
      const double mi = p.masses[i], mj = p.masses[j], ri = p.densities[i], rj = p.densities[j];
      const double expect = 2 * (mi * mj / (mi + mj)) * ((ri + rj) / (ri * rj)) *
                            (r2 / (r2 + 0.01 * 2.5 * 2.5)) * lucy_f(std::sqrt(r2), 2.5, 2);
      EXPECT_NEAR(g.edges[k].weight, expect, 1e-12 * expect);
      ++checked;
    }
  }
  EXPECT_GT(checked, 64u * 10);
}

TEST(DiffusionGraph, VolumeConventionHasDetailedBalanceWithVolumes) {
  ParticleState p = testing::make_lattice(3, 5, 1.0, 0.25, 0.4, 5);
  Model m = testing::diffusion_model(testing::make_box(3, 5.0, false), 1.8, 1.0);
  const DiffusionGraph g = DiffusionGraph::build(m, p);
  for (std::uint32_t i = 0; i < g.size(); ++i) {
    for (auto k = g.row_start[i]; k < g.row_start[i + 1]; ++k) {
      const std::uint32_t j = g.edges[k].target;
      EXPECT_NEAR(g.edges[k].weight * g.volume[i], weight(g, j, i) * g.volume[j],
                  1e-12 * g.edges[k].weight * g.volume[i]);
    }
  }
}

// On a uniform lattice both conventions give 2 V F reg, and sum_j D_0j r_j^2 = 2 d ratio
// (the exact MSD growth rate per unit kappa), ratio from refs/sph_consistency.csv.
TEST(DiffusionGraph, LatticeSecondMomentMatchesSphConsistencyTable) {
  for (int d = 1; d <= 3; ++d) {
    for (double hdx : {1.8, 3.0}) {
      const int n = d == 3 ? 10 : 16;
      const double dx = 0.5;
      const ParticleState p = testing::make_lattice(d, n, dx);
      for (auto conv : {JumpConvention::kSymmetric, JumpConvention::kVolume}) {
        Model m = testing::diffusion_model(testing::make_box(d, n * dx, true), hdx * dx, 1.0, conv);
        const DiffusionGraph g = DiffusionGraph::build(m, p);
        const std::uint32_t i = 0;
        double second = 0;
        for (auto k = g.row_start[i]; k < g.row_start[i + 1]; ++k) {
          double r2 = 0;
          for (int a = 0; a < d; ++a) {
            double x = p.positions[3 * g.edges[k].target + a] - p.positions[a];
            x -= n * dx * std::round(x / (n * dx));
            r2 += x * x;
          }
          second += g.edges[k].weight * r2;
        }
        EXPECT_NEAR(second / (2 * d), testing::kappa_ratio(d, 0.01, hdx), 1e-10)
            << "d=" << d << " h/dx=" << hdx << " " << to_string(conv);
      }
    }
  }
}

TEST(DiffusionGraph, WallTargetsComeLastAndSumsAgree) {
  ParticleState p = testing::make_lattice(2, 6, 1.0, 0.2, 0.0, 9);
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.positions[3 * i] < 1.0) p.kinds[i] = ParticleKind::kWall;
  }
  Model m = testing::diffusion_model(testing::make_box(2, 6.0, false), 2.1, 1.0);
  const DiffusionGraph g = DiffusionGraph::build(m, p);
  for (std::uint32_t i = 0; i < g.size(); ++i) {
    double all = 0, nowall = 0;
    for (auto k = g.row_start[i]; k < g.row_start[i + 1]; ++k) {
      EXPECT_EQ(g.is_wall[g.edges[k].target] != 0, k >= g.split[i]);
      all += g.edges[k].weight;
      if (k < g.split[i]) nowall += g.edges[k].weight;
    }
    EXPECT_NEAR(all, g.sum_all[i], 1e-12 * all);
    EXPECT_NEAR(nowall, g.sum_nowall[i], 1e-12 * all + 1e-300);
  }
}

TEST(GraphJson, DumpHasTheRdmeLinearMeanFormat) {
  const ParticleState p = testing::make_lattice(1, 5, 1.0);
  Model m = testing::diffusion_model(testing::make_box(1, 5.0, false), 1.5, 0.7);
  const DiffusionGraph g = DiffusionGraph::build(m, p);
  LinearRdmeSpec spec;
  spec.kappa = 0.7;
  spec.decay = 0.1;
  spec.birth = {5.0};
  spec.x0 = {10, 0, 0, 0, 0};
  spec.times = {0.5, 1.0};
  const auto j = nlohmann::json::parse(graph_to_json(g, spec));
  EXPECT_EQ(j.at("n_voxels").get<int>(), 5);
  ASSERT_EQ(j.at("edges").size(), 8u);  // 4 bonds, both directions
  for (const auto& e : j.at("edges")) {
    const auto i = e[0].get<std::uint32_t>(), k = e[1].get<std::uint32_t>();
    EXPECT_DOUBLE_EQ(e[2].get<double>(), 0.7 * weight(g, i, k));
  }
  EXPECT_DOUBLE_EQ(j.at("k").get<double>(), 0.1);
  EXPECT_DOUBLE_EQ(j.at("b").get<double>(), 5.0);
  EXPECT_EQ(j.at("x0").size(), 5u);
  EXPECT_EQ(j.at("times").size(), 2u);
}

// The graph (half-stencil pair search, or the full-stencil path when a periodic axis has
// < 3 cells) has exactly the brute-force pairs, weights from the formulas, rows with the
// non-wall targets first, and consistent sums and wall distances.
TEST(DiffusionGraph, EdgesEqualBruteForcePairsInEveryGeometry) {
  for (int dim = 1; dim <= 3; ++dim) {
    for (bool periodic : {false, true}) {
      for (double h : {1.3, 3.4}) {
        for (auto conv : {JumpConvention::kVolume, JumpConvention::kSymmetric}) {
          Box box = testing::make_box(dim, 10.0, periodic);
          if (dim > 1) box.hi[1] = 7.0;  // 3.4 on a periodic 7-long axis: 2 cells
          std::mt19937_64 gen(7 + dim);
          const std::size_t n = dim == 1 ? 40 : dim == 2 ? 200 : 400;
          ParticleState p;
          p.dimension = dim;
          p.resize(n, false);
          std::uniform_real_distribution<double> u01(0.0, 1.0);
          for (std::size_t i = 0; i < n; ++i) {
            for (int a = 0; a < dim; ++a) {
              p.positions[3 * i + a] = box.lo[a] + (box.hi[a] - box.lo[a]) * u01(gen);
            }
            p.masses[i] = 0.5 + u01(gen);
            p.densities[i] = 0.8 + 0.4 * u01(gen);
            if (i % 5 == 0) p.kinds[i] = ParticleKind::kWall;
          }
          Model m = testing::diffusion_model(box, h, 1.0, conv);
          const DiffusionGraph g = DiffusionGraph::build(m, p);
          const NeighborList nl = brute_force_neighbor_list(box, p.positions, h);
          const std::string where = "dim " + std::to_string(dim) + " periodic " +
                                    std::to_string(periodic) + " h " + std::to_string(h);
          for (std::uint32_t i = 0; i < n; ++i) {
            std::vector<std::pair<std::uint32_t, double>> expect, got;
            double wall_r = std::numeric_limits<double>::infinity();
            for (auto k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k) {
              const std::uint32_t j = nl.col[k];
              const double r2 = nl.r2[k], reg = r2 / (r2 + 0.01 * h * h);
              const double f = lucy_f(std::sqrt(r2), h, dim);
              const double vj = p.masses[j] / p.densities[j];
              const double mi = p.masses[i], mj = p.masses[j];
              const double ri = p.densities[i], rj = p.densities[j];
              const double w = conv == JumpConvention::kVolume
                                   ? 2 * vj * reg * f
                                   : 2 * (mi * mj / (mi + mj)) * ((ri + rj) / (ri * rj)) * reg * f;
              expect.emplace_back(j, w);
              if (p.kinds[j] == ParticleKind::kWall) wall_r = std::min(wall_r, std::sqrt(r2));
            }
            double all = 0, nowall = 0;
            for (auto k = g.row_start[i]; k < g.row_start[i + 1]; ++k) {
              const std::uint32_t j = g.edges[k].target;
              ASSERT_EQ(g.is_wall[j] != 0, k >= g.split[i]) << where;
              const double w = g.edges[k].weight;  // a copy: Edge is packed (misaligned)
              got.emplace_back(j, w);
              all += w;
              if (k < g.split[i]) nowall += w;
            }
            std::sort(expect.begin(), expect.end());
            std::sort(got.begin(), got.end());
            ASSERT_EQ(got.size(), expect.size()) << where << " particle " << i;
            for (std::size_t k = 0; k < got.size(); ++k) {
              ASSERT_EQ(got[k].first, expect[k].first) << where;
              // (1 - q)^2 cancels near the cutoff: absolute round-off ~ eps * F(0).
              ASSERT_NEAR(got[k].second, expect[k].second,
                          1e-12 * (expect[k].second + 8 * lucy_f(0.0, h, dim)))
                  << where;
            }
            EXPECT_NEAR(g.sum_all[i], all, 1e-12 * all) << where;
            EXPECT_NEAR(g.sum_nowall[i], nowall, 1e-12 * all) << where;
            if (std::isinf(wall_r)) {
              EXPECT_TRUE(std::isinf(g.wall_distance[i])) << where;
            } else {
              EXPECT_NEAR(g.wall_distance[i], wall_r, 1e-12 * h) << where;
            }
          }
        }
      }
    }
  }
}

}  // namespace
}  // namespace sadr::ssa
