// SPDX-License-Identifier: MIT
// GraphBuilder (Verlet candidate list with a skin): with moving particles the
// per-step graph is exactly the graph of a fresh search (bit for bit), its edge
// set is the brute-force set of pairs within h, the candidate list is reused
// while particles move less than skin/2, and a snapshot taken after a reused
// rebuild restores bit-identically (the graph does not depend on the history).
#include "sadr/ssa/graph_builder.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "sadr/ssa/neighbor_list.hpp"
#include "sadr/ssa/nsm_solver.hpp"
#include "ssa_test_support.hpp"

namespace sadr::ssa {
namespace {

/// Bitwise equality of two graphs (rows, order, weights, sums, wall distances).
void expect_same_graph(const DiffusionGraph& a, const DiffusionGraph& b, const std::string& where) {
  ASSERT_EQ(a.row_start, b.row_start) << where;
  ASSERT_EQ(a.split, b.split) << where;
  ASSERT_EQ(a.edges.size(), b.edges.size()) << where;
  ASSERT_EQ(0, std::memcmp(a.edges.data(), b.edges.data(), a.edges.size() * sizeof(a.edges[0])))
      << where;
  ASSERT_EQ(0, std::memcmp(a.sum_all.data(), b.sum_all.data(), a.sum_all.size() * 8)) << where;
  ASSERT_EQ(0, std::memcmp(a.sum_nowall.data(), b.sum_nowall.data(), a.sum_nowall.size() * 8))
      << where;
  ASSERT_EQ(0,
            std::memcmp(a.wall_distance.data(), b.wall_distance.data(), a.wall_distance.size() * 8))
      << where;
}

/// Directed pairs (i, j) within h by brute force.
std::set<std::pair<std::uint32_t, std::uint32_t>> brute_pairs(const Box& box,
                                                              const ParticleState& p, double h) {
  const NeighborList nl = brute_force_neighbor_list(box, p.positions, h);
  std::set<std::pair<std::uint32_t, std::uint32_t>> out;
  for (std::uint32_t i = 0; i + 1 < nl.row_start.size(); ++i) {
    for (auto k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k) out.emplace(i, nl.col[k]);
  }
  return out;
}

TEST(GraphBuilder, MovingParticlesGiveTheFreshGraphAndTheBruteForceEdges) {
  for (int dim = 1; dim <= 3; ++dim) {
    for (bool periodic : {true, false}) {
      for (JumpConvention conv : {JumpConvention::kVolume, JumpConvention::kSymmetric}) {
        const double len = 10.0, h = dim == 1 ? 1.1 : 1.7;
        const Box box = testing::make_box(dim, len, periodic);
        const std::size_t n = dim == 1 ? 60 : dim == 2 ? 250 : 350;
        std::mt19937_64 gen(11 + dim + (periodic ? 10 : 0));
        std::uniform_real_distribution<double> u01(0.0, 1.0);
        std::normal_distribution<double> step(0.0, 0.002 * h);
        ParticleState p;
        p.dimension = dim;
        p.resize(n, false);
        for (std::size_t i = 0; i < n; ++i) {
          for (int a = 0; a < dim; ++a) p.positions[3 * i + a] = len * (0.05 + 0.9 * u01(gen));
          p.masses[i] = 0.5 + u01(gen);
          p.densities[i] = 0.8 + 0.4 * u01(gen);
          if (i % 7 == 0) p.kinds[i] = ParticleKind::kWall;
        }
        const Model m = testing::diffusion_model(box, h, 1.0, conv);
        GraphBuilder builder;
        DiffusionGraph g;
        for (int it = 0; it < 24; ++it) {
          const std::string where = "dim " + std::to_string(dim) + " periodic " +
                                    std::to_string(periodic) + " step " + std::to_string(it);
          if (it > 0) {
            for (std::size_t i = 0; i < n; ++i) {
              if (p.kinds[i] == ParticleKind::kWall) continue;  // walls do not move
              for (int a = 0; a < dim; ++a) {
                double& x = p.positions[3 * i + a];
                // A large jump now and then forces a new search.
                x += (it % 9 == 0 && i % 50 == 1) ? 0.3 * h : step(gen);
                if (periodic && it % 5 == 0 && i % 9 == 2) x += len;  // unwrapped images
                if (!periodic) x = std::clamp(x, 0.0, len);
              }
            }
          }
          builder.build(g, m, p);
          const DiffusionGraph fresh = DiffusionGraph::build(m, p);
          expect_same_graph(g, fresh, where);
          std::set<std::pair<std::uint32_t, std::uint32_t>> got;
          for (std::uint32_t i = 0; i < n; ++i) {
            for (auto k = g.row_start[i]; k < g.row_start[i + 1]; ++k)
              got.emplace(i, g.edges[k].target);
          }
          ASSERT_EQ(got, brute_pairs(box, p, h)) << where;
        }
        EXPECT_EQ(builder.builds(), 24u);
        EXPECT_GE(builder.searches(), 3u);   // the first call and the large jumps
        EXPECT_LT(builder.searches(), 12u);  // reused in between
      }
    }
  }
}

TEST(GraphBuilder, SolverGraphEqualsFreshBuildAndSnapshotAfterReuseRestores) {
  Model m = testing::diffusion_model(testing::make_box(2, 12.0, true), 2.5, 0.5);
  m.species = {{"A", 0.5}, {"B", 0.2}};
  m.reactions = {{"ab", {{0, 1}}, {{1, 1}}, 0.1, {}, {}}, {"ba", {{1, 1}}, {{0, 1}}, 0.3, {}, {}}};
  ParticleState p = testing::make_lattice(2, 12, 1.0, 0.2, 0.2, 5);
  NsmSolver a(m, 42);
  a.update_graph(p);
  a.set_counts(0, std::vector<std::int64_t>(p.size(), 7));
  std::mt19937_64 gen(3);
  std::normal_distribution<double> step(0.0, 0.005);
  auto move = [&](ParticleState& q) {
    for (double& x : q.positions) x += step(gen);
  };
  for (int k = 0; k < 5; ++k) {
    a.advance(a.time() + 0.3);
    move(p);
    a.update_graph(p);
    expect_same_graph(a.graph(), DiffusionGraph::build(m, p), "step " + std::to_string(k));
  }
  ASSERT_LT(a.state().graph_builder().searches(), a.state().graph_builder().builds());
  const std::string blob = a.save();
  NsmSolver b(m, 1);  // restore searches afresh: must give the same graph and trajectory
  b.restore(blob);
  const ParticleState q0 = p;
  for (NsmSolver* s : {&a, &b}) {
    ParticleState q = q0;
    std::mt19937_64 g2(9);
    std::normal_distribution<double> st(0.0, 0.005);
    for (int k = 0; k < 3; ++k) {
      s->advance(s->time() + 0.4);
      for (double& x : q.positions) x += st(g2);
      s->update_graph(q);
    }
    s->advance(s->time() + 0.4);
  }
  EXPECT_EQ(a.save(), b.save());
  EXPECT_GT(a.events(), 1000u);
}

}  // namespace
}  // namespace sadr::ssa
