// SPDX-License-Identifier: MIT
// Morris-extrapolated Dirichlet walls (Model::morris_walls): the shared geometry
// (common/wall_surface.hpp), the beta-scaled graph edges, validation.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

#include "sadr/common/status.hpp"
#include "sadr/common/wall_surface.hpp"
#include "sadr/ssa/nsm_solver.hpp"
#include "ssa_test_support.hpp"

namespace sadr::ssa {
namespace {

using testing::message_of;

/// An edge's weight by value: DiffusionGraph::Edge is packed (4-byte aligned), so
/// EXPECT_EQ's reference to the double itself would be misaligned (UBSan).
double weight(const DiffusionGraph::Edge& e) {
  return e.weight;
}

TEST(WallSurface, PlaneAndCircleDistancesAndDepths) {
  const WallSurface plane{{0.75, 0, 0}, {1, 0, 0}, 0.0};
  const double front[3] = {1.5, 7, -2}, behind[3] = {0.5, 3, 1};
  EXPECT_DOUBLE_EQ(plane.signed_distance(front), 0.75);
  EXPECT_DOUBLE_EQ(plane.signed_distance(behind), -0.25);
  EXPECT_DOUBLE_EQ(plane.depth(behind), 0.25);
  EXPECT_DOUBLE_EQ(plane.depth(front), 0.0);             // on the fluid side: no depth
  const WallSurface tilted{{0, 1, 0}, {0, -1, 0}, 0.0};  // the top wall y = 1, fluid below
  const double below[3] = {0.3, 0.9, 0};
  EXPECT_NEAR(tilted.signed_distance(below), 0.1, 1e-15);
  // a circle of radius 0.1 around (0.5, 0.5), the fluid outside: radial distances at any angle
  const WallSurface circle{{0.5, 0.5, 0}, {1, 0, 0}, 0.1};
  const double c = 0.12 / std::sqrt(2.0), inside = 0.095 / std::sqrt(2.0);
  const double out[3] = {0.5 + c, 0.5 - c, 0}, in[3] = {0.5 - inside, 0.5 + inside, 0};
  EXPECT_NEAR(circle.signed_distance(out), 0.02, 1e-15);
  EXPECT_NEAR(circle.depth(in), 0.005, 1e-15);
}

TEST(WallSurface, MorrisBetaIsOnePlusTheDistanceRatioCappedAtOneAndAHalf) {
  const double h = 3.0;
  EXPECT_DOUBLE_EQ(morris_beta(0.25, 0.75, h), 1.0 + 0.25 / 0.75);
  EXPECT_DOUBLE_EQ(morris_beta(0.0, 0.75, h), 1.0);  // a wall particle on the surface
  EXPECT_DOUBLE_EQ(morris_beta(1.0, 1.0, h), 1.5);   // 2 capped
  EXPECT_DOUBLE_EQ(morris_beta(1e-6, -0.5, h), 1.0 + 1e-6 / 3e-3);  // d_i floored at 1e-3 h
}

// 1D chain of 12 (dx = 1, h = 1.5: nearest neighbours), walls 0 and 11 at x = 0.5 and 11.5,
// their surfaces at x = 0.75 (beta 1 + 0.25/0.75) and x = 11.3 (beta 1 + 0.2/0.8).
struct Chain {
  Model model = testing::diffusion_model(testing::make_box(1, 12.0, false), 1.5, 1.0);
  ParticleState p = testing::make_lattice(1, 12, 1.0);
  Chain() {
    p.kinds[0] = p.kinds[11] = ParticleKind::kWall;
    model.reservoirs = {{0, 40.0, {0}}, {0, 0.0, {11}}};
  }
  void add_surfaces() {
    model.morris_walls = {{{0}, {{0.75, 0, 0}, {1, 0, 0}, 0.0}},
                          {{11}, {{11.3, 0, 0}, {-1, 0, 0}, 0.0}}};
  }
};

TEST(MorrisWalls, EdgesBetweenFluidAndSurfaceWallsAreScaledByBetaBothWays) {
  Chain plain, morris;
  morris.add_surfaces();
  NsmSolver a(plain.model, 1), b(morris.model, 1);
  a.update_graph(plain.p);
  b.update_graph(morris.p);
  const DiffusionGraph &ga = a.graph(), &gb = b.graph();
  ASSERT_EQ(ga.edge_count(), gb.edge_count());
  const double beta_l = 1.0 + 0.25 / 0.75, beta_r = 1.0 + 0.2 / 0.8;
  for (std::uint32_t i = 0; i < 12; ++i) {
    double sum = 0, nowall = 0;
    for (std::uint32_t k = ga.row_start[i]; k < ga.row_start[i + 1]; ++k) {
      const std::uint32_t j = ga.edges[k].target;
      ASSERT_EQ(gb.edges[k].target, j);
      const std::uint32_t lo = std::min(i, j), hi = std::max(i, j);
      const double beta = (lo == 0 && hi == 1) ? beta_l : (lo == 10 && hi == 11) ? beta_r : 1.0;
      EXPECT_NEAR(gb.edges[k].weight, beta * ga.edges[k].weight, 1e-12 * ga.edges[k].weight)
          << i << " -> " << j;
      sum += gb.edges[k].weight;
      if (!gb.is_wall[j]) nowall += gb.edges[k].weight;
    }
    EXPECT_NEAR(gb.sum_all[i], sum, 1e-12 * sum) << i;
    EXPECT_NEAR(gb.sum_nowall[i], nowall, 1e-12 * sum + 1e-300) << i;
  }
  // The reservoir's emission rate into voxel 1 and voxel 1's absorption rate both carry beta:
  // the cached rate of wall 0 is kappa X_0 sum_nowall = 40 beta_l w.
  EXPECT_NEAR(b.voxel_rate(0), beta_l * a.voxel_rate(0), 1e-12 * a.voxel_rate(0));
}

TEST(MorrisWalls, PerParticleTangentPlanesGiveTheEdgesOfTheEquivalentSurfaces) {
  // Walls made by a scene's geometry: the same two planes as one tangent plane per wall voxel
  // (depth 0.25 behind x = 0.75, 0.2 behind x = 11.3) scale the same edges by the same beta, to
  // rounding.
  Chain planes, tangents;
  planes.add_surfaces();
  tangents.model.morris_tangents.particles = {0, 11};
  tangents.model.morris_tangents.depths = {0.25, 0.2};
  tangents.model.morris_tangents.normals = {1, 0, 0, -1, 0, 0};
  NsmSolver a(planes.model, 1), b(tangents.model, 1);
  a.update_graph(planes.p);
  b.update_graph(tangents.p);
  ASSERT_EQ(a.graph().edge_count(), b.graph().edge_count());
  for (std::size_t k = 0; k < a.graph().edge_count(); ++k) {
    const double w = a.graph().edges[k].weight;
    EXPECT_NEAR(b.graph().edges[k].weight, w, 1e-13 * w) << k;
  }
  for (std::uint32_t i = 0; i < 12; ++i) {
    EXPECT_NEAR(b.graph().sum_all[i], a.graph().sum_all[i], 1e-13 * a.graph().sum_all[i]);
  }
  // Not together with region surfaces; bad arrays are refused by name.
  tangents.model.morris_walls = planes.model.morris_walls;
  EXPECT_NE(message_of([&] { tangents.model.validate(); }).find("not together with morris_walls"),
            std::string::npos);
  tangents.model.morris_walls.clear();
  tangents.model.morris_tangents.normals[0] = 2;
  EXPECT_NE(message_of([&] {
              tangents.model.validate();
            }).find("morris_wall_tangents[0].normal has length 2"),
            std::string::npos);
}

TEST(MorrisWalls, TheFirstListedSurfaceWinsAndFluidVoxelsAreIgnored) {
  Chain c;
  // voxel 0 listed by a far plane after the right one; fluid voxel 1 listed too (ignored)
  c.model.morris_walls = {{{0, 1}, {{0.75, 0, 0}, {1, 0, 0}, 0.0}},
                          {{0, 11}, {{5.0, 0, 0}, {1, 0, 0}, 0.0}}};
  Chain ref;
  ref.model.morris_walls = {{{0}, {{0.75, 0, 0}, {1, 0, 0}, 0.0}},
                            {{11}, {{5.0, 0, 0}, {1, 0, 0}, 0.0}}};
  NsmSolver a(c.model, 1), b(ref.model, 1);
  a.update_graph(c.p);
  b.update_graph(ref.p);
  for (std::size_t k = 0; k < a.graph().edge_count(); ++k) {
    EXPECT_EQ(weight(a.graph().edges[k]), weight(b.graph().edges[k])) << k;
  }
  // wall 11 on the fluid side of x = 5 (depth 0): beta 1, its edges unscaled
  Chain plain;
  NsmSolver p(plain.model, 1);
  p.update_graph(plain.p);
  const auto& g = a.graph();
  EXPECT_EQ(weight(g.edges[g.row_start[11]]), weight(p.graph().edges[p.graph().row_start[11]]));
}

TEST(MorrisWalls, TheGraphFollowsTheParticles) {
  Chain c;
  c.add_surfaces();
  NsmSolver s(c.model, 1);
  s.update_graph(c.p);
  const DiffusionGraph& g = s.graph();
  const double w0 = g.edges[g.row_start[0]].weight;
  c.p.positions[3 * 1] = 1.25;  // fluid voxel 1 moves to 0.5 in front of the surface: beta 1.5
  s.update_graph(c.p);
  Chain plain;
  plain.p.positions[3 * 1] = 1.25;
  NsmSolver p(plain.model, 1);
  p.update_graph(plain.p);
  const double w = p.graph().edges[p.graph().row_start[0]].weight;
  EXPECT_NEAR(s.graph().edges[s.graph().row_start[0]].weight, 1.5 * w, 1e-12 * w);
  EXPECT_NE(weight(s.graph().edges[s.graph().row_start[0]]), w0);
}

TEST(MorrisWalls, ValidationNamesTheField) {
  Chain c;
  c.add_surfaces();
  c.model.morris_walls[1].surface.inward_normal = {2, 0, 0};
  EXPECT_NE(message_of([&] {
              c.model.validate();
            }).find("morris_walls[1].surface.inward_normal has length 2"),
            std::string::npos);
  c.add_surfaces();
  c.model.morris_walls[0].surface.radius = -1;
  EXPECT_NE(message_of([&] { c.model.validate(); }).find("morris_walls[0].surface.radius = -1"),
            std::string::npos);
  c.add_surfaces();
  c.model.morris_walls[0].voxels.clear();
  EXPECT_NE(message_of([&] { c.model.validate(); }).find("morris_walls[0].voxels: empty"),
            std::string::npos);
  c.add_surfaces();
  c.model.free_walls = {{0, {}}};
  c.model.reservoirs.clear();
  EXPECT_NE(message_of([&] { c.model.validate(); }).find("together with free_walls"),
            std::string::npos);
  c.model.free_walls.clear();
  c.model.morris_walls[1].voxels = {12};
  NsmSolver s(c.model, 1);
  EXPECT_NE(message_of([&] { s.update_graph(c.p); }).find("morris_walls[1].voxels contains 12"),
            std::string::npos);
  EXPECT_FALSE(s.state().has_graph());  // checked before anything was built
}

TEST(MorrisWalls, TheFingerprintSeesTheSurfaces) {
  Chain a, b;
  b.add_surfaces();
  EXPECT_NE(a.model.fingerprint(), b.model.fingerprint());
  Chain c;
  c.add_surfaces();
  c.model.morris_walls[0].surface.point[0] = 0.7;
  EXPECT_NE(b.model.fingerprint(), c.model.fingerprint());
}

}  // namespace
}  // namespace sadr::ssa
