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
#include <map>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "graph_build_detail.hpp"  // private (ssa_service/core/src): the full-stencil path
#include "graph_filter.hpp"
#include "sadr/common/status.hpp"
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

/// Random particles in a box of side len (some walls, varied m and rho, one
/// coincident pair, which must carry no edge), moved by `jitter` per axis per call.
struct Cloud {
  ParticleState p;
  std::mt19937_64 gen;
  Cloud(int dim, std::size_t n, double len, std::uint64_t seed) : gen(seed) {
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    p.dimension = dim;
    p.resize(n, false);
    for (std::size_t i = 0; i < n; ++i) {
      for (int a = 0; a < dim; ++a) p.positions[3 * i + a] = len * (0.02 + 0.96 * u01(gen));
      p.masses[i] = 0.5 + u01(gen);
      p.densities[i] = 0.8 + 0.4 * u01(gen);
      if (i % 11 == 3) p.kinds[i] = ParticleKind::kWall;
    }
    for (int a = 0; a < dim; ++a) p.positions[3 * 1 + a] = p.positions[a];  // 0 and 1 coincide
  }
  void move(double jitter, double len) {
    std::normal_distribution<double> step(0.0, jitter);
    for (std::size_t i = 2; i < p.size(); ++i) {
      for (int a = 0; a < p.dimension; ++a) {
        double& x = p.positions[3 * i + a];
        x = std::clamp(x + step(gen), 0.0, len);
      }
    }
  }
};

TEST(GraphBuilder, SimdSearchAndFilterGiveTheScalarGraphBitForBit) {
  if (!detail::filter_simd_available()) GTEST_SKIP() << "no AVX-512F on this CPU";
  for (int dim = 1; dim <= 3; ++dim) {
    for (bool periodic : {true, false}) {
      for (JumpConvention conv : {JumpConvention::kVolume, JumpConvention::kSymmetric}) {
        for (double reg : {0.0, 0.01}) {
          const double len = 10.0, h = dim == 1 ? 0.9 : dim == 2 ? 1.3 : 1.9;
          Cloud c(dim, dim == 1 ? 120 : 600, len, 5 + dim);
          Model m = testing::diffusion_model(testing::make_box(dim, len, periodic), h, 1.0, conv);
          m.regularization = reg;
          GraphBuilder scalar, simd;
          scalar.set_simd(false);
          DiffusionGraph gs, gv;
          for (int it = 0; it < 6; ++it) {
            const std::string where = "dim " + std::to_string(dim) + " periodic " +
                                      std::to_string(periodic) + " reg " + std::to_string(reg) +
                                      " step " + std::to_string(it);
            scalar.build(gs, m, c.p);
            simd.build(gv, m, c.p);
            expect_same_graph(gs, gv, where);
            ASSERT_GT(gs.edge_count(), 0u) << where;
            // The vectorised search gives the same candidate rows too.
            ASSERT_EQ(scalar.candidate_count(), simd.candidate_count()) << where;
            ASSERT_EQ(scalar.searches(), simd.searches()) << where;
            c.move(0.01 * h, len);
          }
        }
      }
    }
  }
}

TEST(GraphBuilder, GraphDoesNotDependOnTheThreadCount) {
  for (int dim = 2; dim <= 3; ++dim) {
    const double len = dim == 2 ? 40.0 : 14.0, h = 1.5;
    Cloud c(dim, 3100, len, 17 + dim);  // >= 3 x GraphBuilder's 1024 rows per thread
    const Model m = testing::diffusion_model(testing::make_box(dim, len, true), h, 1.0);
    GraphBuilder b1, b2, b3;
    b1.set_threads(1);
    b2.set_threads(2);
    b3.set_threads(3);
    DiffusionGraph g1, g2, g3;
    for (int it = 0; it < 5; ++it) {
      const std::string where = "dim " + std::to_string(dim) + " step " + std::to_string(it);
      b1.build(g1, m, c.p);
      b2.build(g2, m, c.p);
      b3.build(g3, m, c.p, /*force_search=*/it % 2 == 1);
      expect_same_graph(g1, g2, where);
      expect_same_graph(g1, g3, where);
      if (it == 4) {
        std::set<std::pair<std::uint32_t, std::uint32_t>> got;
        for (std::uint32_t i = 0; i < g3.size(); ++i) {
          for (auto k = g3.row_start[i]; k < g3.row_start[i + 1]; ++k)
            got.emplace(i, g3.edges[k].target);
        }
        auto want = brute_pairs(m.box, c.p, h);
        want.erase({0, 1});  // the coincident pair: no edge (zero weight)
        want.erase({1, 0});
        ASSERT_EQ(got, want) << where;
      }
      c.move(it == 2 ? 0.2 * h : 0.01 * h, len);  // one move beyond the skin: a search
    }
    EXPECT_GE(b2.searches(), 2u);
  }
}

// The threaded rebuild validates inside its parallel region: a bad particle must
// still throw the usual InvalidArgument there and leave graph and builder usable.
TEST(GraphBuilder, InvalidParticleOnTheThreadedRebuildThrowsAndLeavesTheGraph) {
  const double len = 40.0, h = 1.5;
  Cloud c(2, 3100, len, 5);
  const Model m = testing::diffusion_model(testing::make_box(2, len, true), h, 1.0);
  GraphBuilder b;
  b.set_threads(2);
  DiffusionGraph g;
  b.build(g, m, c.p);
  c.move(0.002 * h, len);  // well inside the skin: no search
  b.build(g, m, c.p);      // the candidate list is reused: the threaded path
  const DiffusionGraph before = g;
  const std::uint64_t searches = b.searches();
  ParticleState bad = c.p;
  bad.densities[2500] = -1.0;
  try {
    b.build(g, m, bad);
    FAIL() << "no exception for a negative density";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("density = -1"), std::string::npos) << e.what();
  }
  expect_same_graph(g, before, "after the failed rebuild");
  c.move(0.002 * h, len);  // well inside the skin: no search
  b.build(g, m, c.p);
  expect_same_graph(g, DiffusionGraph::build(m, c.p), "rebuild after the error");
  EXPECT_EQ(b.searches(), searches);  // the candidate list survived
}

TEST(GraphBuilder, WeightsEqualTheFullStencilPathBitForBit) {
  // An independent code path (diffusion_graph.cpp's cell-order rows with weights
  // computed on the fly): same edge set, same weights and wall distances per edge.
  for (int dim = 1; dim <= 3; ++dim) {
    for (JumpConvention conv : {JumpConvention::kVolume, JumpConvention::kSymmetric}) {
      const double len = 10.0, h = dim == 1 ? 0.9 : 1.6;
      Cloud c(dim, dim == 1 ? 100 : 500, len, 31 + dim);
      const Model m = testing::diffusion_model(testing::make_box(dim, len, true), h, 1.0, conv);
      DiffusionGraph fast, ref;
      GraphBuilder b;
      b.build(fast, m, c.p);
      detail::prepare_vertices(ref, c.p);
      detail::build_rows_full_stencil(ref, m, c.p);
      ASSERT_EQ(fast.edge_count(), ref.edge_count());
      for (std::uint32_t i = 0; i < fast.size(); ++i) {
        std::map<std::uint32_t, double> want;
        for (auto k = ref.row_start[i]; k < ref.row_start[i + 1]; ++k)
          want[ref.edges[k].target] = ref.edges[k].weight;
        ASSERT_EQ(fast.row_start[i + 1] - fast.row_start[i], want.size()) << "row " << i;
        for (auto k = fast.row_start[i]; k < fast.row_start[i + 1]; ++k) {
          ASSERT_EQ(want.count(fast.edges[k].target), 1u) << "row " << i;
          ASSERT_EQ(std::memcmp(&want[fast.edges[k].target], &fast.edges[k].weight, 8), 0)
              << "row " << i << " target " << fast.edges[k].target;
        }
        ASSERT_EQ(std::memcmp(&fast.wall_distance[i], &ref.wall_distance[i], 8), 0) << i;
      }
    }
  }
}

}  // namespace
}  // namespace sadr::ssa
