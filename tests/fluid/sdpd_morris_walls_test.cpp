// SPDX-License-Identifier: MIT
// Morris, Fox & Zhu (1997) extrapolated wall velocity: the distances d_i, d_j to a planar and to a
// curved (circle) wall surface, and the factor beta = min(1.5, 1 + d_j/d_i) they give.
#include <gtest/gtest.h>

#include <cmath>

#include "sadr/common/particle_state.hpp"
#include "sadr/fluid/fluid_model.hpp"
#include "sadr/fluid/species_transport.hpp"
#include "sdpd/sdpd_morris_walls.hpp"

namespace sadr::fluid {
namespace {

// Two wall particles of one region: at radius 0.095 from (0.5, 0.5) on the +y axis and on the
// diagonal; a circle of radius 0.1 puts both 0.005 behind the surface.
struct Disk {
  FluidModel model;
  ParticleState state;
  Disk(double radius, std::array<double, 3> normal) {
    model.box.dimension = 2;
    model.wall_model = WallModel::kMorrisExtrapolated;
    WallRegion reg;
    reg.name = "cylinder";
    reg.particles = {0, 1};
    reg.surface_point =
        radius > 0 ? std::array<double, 3>{0.5, 0.5, 0} : std::array<double, 3>{0.5, 0.6, 0};
    reg.inward_normal = normal;
    reg.surface_radius = radius;
    model.wall_regions.push_back(reg);
    state.resize(2);
    const double r = 0.095, c = r / std::sqrt(2.0);
    state.positions = {0.5, 0.5 + r, 0, 0.5 + c, 0.5 + c, 0};
    state.kinds = {ParticleKind::kWall, ParticleKind::kWall};
  }
};

TEST(MorrisWalls, CircleMeasuresRadialDistancesAtEveryAngle) {
  Disk d(0.1, {1, 0, 0});
  MorrisWalls walls;
  walls.setup(d.model, d.state);
  ASSERT_TRUE(walls.enabled());
  const double h = 0.037;
  // fluid particles 0.02 outside the circle: beta = 1 + 0.005 / 0.02 = 1.25 for both pairs
  const double r = 0.12, c = r / std::sqrt(2.0);
  const double above[3] = {0.5, 0.5 + r, 0}, diagonal[3] = {0.5 + c, 0.5 + c, 0};
  EXPECT_NEAR(walls.beta(above, 0, h), 1.25, 1e-12);
  EXPECT_NEAR(walls.beta(diagonal, 1, h), 1.25, 1e-12);
  EXPECT_NEAR(walls.beta(diagonal, 0, h), 1.25, 1e-12);
  // closer fluid: capped at 1.5 (d_i = 0.002: 1 + 2.5)
  const double close[3] = {0.5, 0.5 + 0.102, 0};
  EXPECT_DOUBLE_EQ(walls.beta(close, 0, h), 1.5);
}

TEST(MorrisWalls, APlaneTangentAtTheTopIsWrongOnTheDiagonal) {
  // the plane y = 0.6 (normal +y) agrees with the circle on the +y axis and not on the diagonal,
  // which is why curved walls need their own surface
  Disk d(0.0, {0, 1, 0});
  MorrisWalls walls;
  walls.setup(d.model, d.state);
  const double h = 0.037, r = 0.12, c = r / std::sqrt(2.0);
  const double above[3] = {0.5, 0.5 + r, 0}, diagonal[3] = {0.5 + c, 0.5 + c, 0};
  EXPECT_NEAR(walls.beta(above, 0, h), 1.25, 1e-12);
  // wall particle 1 lies 0.6 - (0.5 + 0.0672) = 0.0328 below the plane, the fluid particle
  // 0.5 + 0.0849 - 0.6 < 0 below it too: d_i is floored at 1e-3 h and beta capped
  EXPECT_DOUBLE_EQ(walls.beta(diagonal, 1, h), 1.5);
}

TEST(MorrisWalls, TangentPlanesPerParticleMeasureFromThePairDisplacement) {
  // Walls made by a scene's geometry: each wall particle its own tangent plane. On the circle of
  // radius 0.1 the tangent plane of each particle is exact along its own normal line, so the
  // fluid particles on those lines get the circle's beta; d_i comes from the pair displacement.
  Disk d(0.1, {1, 0, 0});
  const double c = 1 / std::sqrt(2.0);
  d.model.wall_tangents.particles = {0, 1};
  d.model.wall_tangents.depths = {0.005, 0.005};
  d.model.wall_tangents.normals = {0, 1, 0, c, c, 0};
  MorrisWalls walls;
  walls.setup(d.model, d.state);
  ASSERT_TRUE(walls.enabled());
  EXPECT_TRUE(walls.extrapolates(0) && walls.extrapolates(1));
  const double h = 0.037, r = 0.12, rc = r / std::sqrt(2.0);
  const double above[3] = {0.5, 0.5 + r, 0}, diagonal[3] = {0.5 + rc, 0.5 + rc, 0};
  auto pair = [&](const double* xi, std::uint32_t j) {
    const double xij[3] = {xi[0] - d.state.positions[3 * j], xi[1] - d.state.positions[3 * j + 1],
                           0};
    return walls.beta<2>(xi, xij, j, h);
  };
  EXPECT_NEAR(pair(above, 0), 1.25, 1e-12);
  EXPECT_NEAR(pair(diagonal, 1), 1.25, 1e-12);
  // off its normal line the plane departs from the circle by about s^2 / (2 R): with s = 0.085
  // on R = 0.1 the diagonal fluid particle (y = 0.585) lies behind particle 0's plane y = 0.6,
  // so d_i is floored at 1e-3 h and beta capped
  EXPECT_DOUBLE_EQ(pair(diagonal, 0), 1.5);
}

// The same extrapolation for a Dirichlet species: the ghost value C_w + (beta - 1)(C_w - C_i)
// multiplies the pair term by beta; a kFree neighbour is not affected.
TEST(MorrisWalls, DirichletSpeciesPairTermIsMultipliedByBeta) {
  FluidModel model;
  model.box.dimension = 2;
  SpeciesSpec theta;
  theta.def.name = "theta";
  theta.def.diffusivity = 0.5;
  theta.default_wall = {WallCondition::Type::kDirichlet, 1.0};
  model.species.push_back(theta);
  ParticleState state;
  state.resize(3);
  state.kinds = {ParticleKind::kFluid, ParticleKind::kWall, ParticleKind::kFluid};
  SpeciesTransport species;
  species.setup(model, state);
  const std::vector<std::vector<double>> c{{0.2, 1.0, 0.6}};
  const double xij[3] = {0.01, 0, 0};
  for (const double beta : {1.0, 1.25, 1.5}) {
    std::vector<std::vector<double>> dc{{0.0, 0.0, 0.0}};
    species.add_pair(0, 1, 2.0, xij, c, dc, beta);  // wall: 2 * (2 * 0.5) * 0.8 * beta
    EXPECT_DOUBLE_EQ(dc[0][0], 1.6 * beta);
    species.add_pair(0, 2, 2.0, xij, c, dc, beta);  // fluid neighbour: + 2 * 1 * 0.4
    EXPECT_DOUBLE_EQ(dc[0][0], 1.6 * beta + 0.8);
  }
}

}  // namespace
}  // namespace sadr::fluid
