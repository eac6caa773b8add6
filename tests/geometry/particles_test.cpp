// SPDX-License-Identifier: MIT
// Lattice fill, wall layers, relaxation and volumes (particles.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "mesh_builders.hpp"
#include "sadr/common/status.hpp"
#include "sadr/geometry/particles.hpp"

namespace sadr::geometry {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(Fill, WholeBoxGivesOneParticlePerCell) {
  FluidDomain d;
  d.box = {{0, 0, 0}, {1, 0.5, 0.25}};
  FillOptions o;
  o.spacing = 0.05;
  const ParticleSet p = fill(d, o);
  EXPECT_EQ(p.count(Kind::kFluid), 20u * 10u * 5u);
  EXPECT_EQ(p.count(Kind::kWall), 0u);
  o.lattice = Lattice::kHexagonal;  // FCC: one particle per spacing^3 up to the box's edges
  const double n_fcc = static_cast<double>(fill(d, o).count(Kind::kFluid));
  EXPECT_NEAR(n_fcc / 1000.0, 1.0, 0.15);
  FluidDomain d2;
  d2.dimension = 2;
  d2.box = {{0, 0, 0}, {1, 1, 0}};
  o.spacing = 0.02;
  const double n_hex = static_cast<double>(fill(d2, o).count(Kind::kFluid));
  EXPECT_NEAR(n_hex / 2500.0, 1.0, 0.05);
}

TEST(Fill, WallLayersKnowTheirSurface) {
  FluidDomain d;
  d.box = {{-1.1, -1.1, -1.1}, {1.1, 1.1, 1.1}};
  d.body = make_sphere({0, 0, 0}, 0.9);
  d.body_surface_id = 5;
  d.solids.push_back({make_cylinder({0, 0, -0.5}, {0, 0, 0.5}, 0.2), 7});
  FillOptions o;
  o.spacing = 0.05;
  o.wall_depth = 0.15;
  const ParticleSet p = fill(d, o);
  std::size_t walls5 = 0, walls7 = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3 x = p.position[i];
    if (p.kind[i] == Kind::kFluid) {
      EXPECT_LT(norm(x), 0.9);
      EXPECT_FALSE(d.solids[0].shape->inside(x));
      // Fluid near a surface knows which one and how far.
      if (p.surface_id[i] == 5) {
        EXPECT_NEAR(p.distance[i], 0.9 - norm(x), 1e-12);
      } else if (p.surface_id[i] == 7) {
        EXPECT_NEAR(p.distance[i], d.solids[0].shape->signed_distance(x), 1e-12);
      } else {
        EXPECT_EQ(p.surface_id[i], -1);
        EXPECT_GT(std::min(0.9 - norm(x), d.solids[0].shape->signed_distance(x)),
                  o.wall_depth + o.spacing);
      }
      continue;
    }
    EXPECT_LE(p.distance[i], o.wall_depth + 1e-12);
    EXPECT_NEAR(norm(p.normal[i]), 1, 1e-9);
    if (p.surface_id[i] == 5) {
      ++walls5;
      EXPECT_NEAR(p.distance[i], norm(x) - 0.9, 1e-12);
      EXPECT_LT(dot(p.normal[i], x), 0);  // into the fluid: towards the centre
    } else {
      ASSERT_EQ(p.surface_id[i], 7);
      ++walls7;
      EXPECT_TRUE(d.solids[0].shape->inside(x));
    }
  }
  // The shell 0.9 < r < 1.05, less its deepest sites that no fluid particle reaches (the first
  // fluid layer lies up to one spacing inside): between the shells of depth 0.1 and 0.15.
  const double shell = static_cast<double>(walls5) * std::pow(o.spacing, 3);
  EXPECT_GT(shell, 4.0 / 3.0 * kPi * (std::pow(1.0, 3) - std::pow(0.9, 3)));
  EXPECT_LT(shell, 4.0 / 3.0 * kPi * (std::pow(1.05, 3) - std::pow(0.9, 3)));
  EXPECT_GT(walls7, 300u);
  // Thread count does not change the result.
  o.threads = 1;
  const ParticleSet p1 = fill(d, o);
  ASSERT_EQ(p1.size(), p.size());
  for (std::size_t i = 0; i < p.size(); i += 97) EXPECT_EQ(p1.position[i].x, p.position[i].x);
}

TEST(Fill, TwoDimensionalMeshBodyWithWalls) {
  FluidDomain d;
  d.dimension = 2;
  d.box = {{-1.2, -1.2, 0}, {1.2, 1.2, 0}};
  d.body = make_mesh_shape(testing::circle_polyline({0, 0, 0}, 1, 512));
  FillOptions o;
  o.spacing = 0.02;
  o.wall_depth = 0.06;
  o.lattice = Lattice::kHexagonal;
  const ParticleSet p = fill(d, o);
  const double area = static_cast<double>(p.count(Kind::kFluid)) * o.spacing * o.spacing;
  EXPECT_NEAR(area / kPi, 1, 0.01);
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_EQ(p.position[i].z, 0);
    if (p.kind[i] == Kind::kWall) {
      EXPECT_NEAR(p.distance[i], norm(p.position[i]) - 1, 2e-4);  // chord error of 512 segments
      EXPECT_LT(p.normal[i].x * p.position[i].x + p.normal[i].y * p.position[i].y, 0);
    }
  }
  EXPECT_GT(p.count(Kind::kWall), 2 * 314u);
}

TEST(Fill, WallsNoFluidSeesAreDropped) {
  FluidDomain d;
  d.box = {{0, 0, 0}, {1, 1, 1}};
  d.body = make_box({0.1, 0.1, 0.1}, {0.5, 0.5, 0.5});
  d.solids.push_back({make_sphere({0.8, 0.8, 0.8}, 0.1), 3});  // far from the fluid
  FillOptions o;
  o.spacing = 0.05;
  o.wall_depth = 0.1;
  const ParticleSet p = fill(d, o);
  for (std::size_t i = 0; i < p.size(); ++i) EXPECT_NE(p.surface_id[i], 3);
}

TEST(Fill, VolumesSumToTheDomainVolume) {
  FluidDomain d;
  d.box = {{0, 0, 0}, {1, 1, 1}};
  d.periodic = {true, true, true};
  d.solids.push_back({make_sphere({0.5, 0.5, 0.5}, 0.2), 1});
  FillOptions o;
  o.spacing = 1.0 / 16;
  o.wall_depth = 2.5 / 16;
  ParticleSet p = fill(d, o);
  const double exact = 1 - 4.0 / 3.0 * kPi * 0.008;
  const double scale = assign_volumes(p, d, 2.5 / 16, exact, 1000.0);
  double sum = 0, mass = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kind[i] == Kind::kFluid) sum += p.volume[i], mass += p.mass[i];
  }
  EXPECT_NEAR(sum, exact, 1e-12);
  EXPECT_NEAR(mass, 1000.0 * exact, 1e-9);
  EXPECT_NEAR(scale, 1, 0.05);
}

TEST(Fill, RefusesBadOptions) {
  FluidDomain d;
  d.box = {{0, 0, 0}, {1, 1, 1}};
  FillOptions o;
  EXPECT_THROW(fill(d, o), InvalidArgument);  // spacing 0
  o.spacing = 0.1;
  d.body = make_sphere({5, 5, 5}, 1);
  EXPECT_THROW(fill(d, o), InvalidArgument);  // body outside the box
  d.body = make_sphere({0, 0, 0}, 1, 2);
  EXPECT_THROW(fill(d, o), InvalidArgument);  // 2D body in a 3D domain
}

}  // namespace
}  // namespace sadr::geometry
