// SPDX-License-Identifier: MIT
// The health checks of `sadr summary` (run_health.hpp) on synthetic frames: a fluid particle put
// inside a wall is found (by the dx/2 test and past a wall plane), a removed block is a hole, a
// uniform lattice has neither, and the density deviation is computed exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "sadr/orchestrator/run_health.hpp"
#include "sadr/orchestrator/scene.hpp"
#include "sadr/orchestrator/scene_loader.hpp"
#include "scene_test_support.hpp"

namespace sadr::orchestrator {
namespace {

constexpr double kDx = 0.1;

void add(ParticleState& p, double x, double y, ParticleKind kind, double rho = 1.0) {
  p.positions.insert(p.positions.end(), {x, y, 0.0});
  p.velocities.insert(p.velocities.end(), {0.0, 0.0, 0.0});
  p.densities.push_back(rho);
  p.masses.push_back(kDx * kDx);
  p.kinds.push_back(kind);
  p.ids.push_back(p.ids.size());
}

/// A 2D channel periodic along x: nx columns, `wall_rows` wall rows below y = 0 (at -dx/2,
/// -3dx/2, ...) and `fluid_rows` fluid rows above (at dx/2, 3dx/2, ...), lattice spacing dx.
ParticleState channel(int nx, int fluid_rows, int wall_rows = 3) {
  ParticleState p;
  p.dimension = 3;
  for (int j = -wall_rows; j < fluid_rows; ++j) {
    for (int i = 0; i < nx; ++i) {
      add(p, (i + 0.5) * kDx, (j + 0.5) * kDx, j < 0 ? ParticleKind::kWall : ParticleKind::kFluid);
    }
  }
  return p;
}

HealthContext context(int nx, double h = 3 * kDx) {
  HealthContext c;
  c.box.dimension = 2;
  c.box.lo = {0, -10, 0};
  c.box.hi = {nx * kDx, 10, 0};
  c.box.periodic = {true, false, false};
  c.spacing = kDx;
  c.support = h;
  c.reference_density = 1.0;
  return c;
}

/// The index of the particle nearest (x, y).
std::size_t at(const ParticleState& p, double x, double y) {
  std::size_t best = 0;
  double r2 = 1e300;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double d2 = std::pow(p.positions[3 * i] - x, 2) + std::pow(p.positions[3 * i + 1] - y, 2);
    if (d2 < r2) {
      r2 = d2;
      best = i;
    }
  }
  return best;
}

TEST(RunHealth, UniformLatticeHasNoPenetrationNoHoleNoDeviation) {
  const ParticleState p = channel(20, 15);
  const HealthContext c = context(20);
  EXPECT_EQ(find_wall_penetration(p, c).count, 0u);
  const HoleResult holes = find_holes(p, c);
  EXPECT_TRUE(holes.checked);
  EXPECT_EQ(holes.count, 0u);
  EXPECT_DOUBLE_EQ(holes.cell, 2.0 / 6);  // periodic: L / floor(L / h) = 2 / floor(6.67)
  const DensityResult rho = density_deviation(p, 1.0);
  EXPECT_EQ(rho.fluid, 20u * 15u);
  EXPECT_EQ(rho.max, 0.0);
  EXPECT_EQ(rho.rms, 0.0);
  EXPECT_NEAR(estimate_spacing(p, c.box), kDx, 1e-12);
}

TEST(RunHealth, LatticeShiftedOffTheGridHasNoHole) {
  // A cell of size >= h > dx always holds a lattice point, wherever the periodic grid starts.
  for (const double shift : {0.013, 0.05, 0.0999}) {
    ParticleState p = channel(20, 15);
    for (std::size_t i = 0; i < p.size(); ++i) p.positions[3 * i] += shift;
    for (const double h : {1.01 * kDx, 1.3 * kDx, 2 * kDx}) {
      EXPECT_EQ(find_holes(p, context(20, h)).count, 0u) << shift << " " << h;
    }
  }
}

TEST(RunHealth, FluidParticleInsideAWallIsFound) {
  ParticleState p = channel(20, 15);
  // Move a fluid particle of the first row to 0.02 from a wall particle of the second layer.
  const std::size_t wall = at(p, 0.55, -0.15);
  const std::size_t fluid = at(p, 0.95, 0.05);
  p.positions[3 * fluid] = 0.55 + 0.02;
  p.positions[3 * fluid + 1] = -0.15;
  ASSERT_EQ(p.kinds[wall], ParticleKind::kWall);
  const PenetrationResult r = find_wall_penetration(p, context(20));
  EXPECT_EQ(r.count, 1u);
  ASSERT_TRUE(r.worst.found);
  EXPECT_EQ(r.worst.id, p.ids[fluid]);
  EXPECT_NEAR(r.worst.value, 0.5 * kDx - 0.02, 1e-12);  // depth past the dx/2 sphere
  EXPECT_NEAR(r.worst.x[0], 0.57, 1e-12);
}

TEST(RunHealth, FluidParticlePastAWallPlaneIsFound) {
  ParticleState p = channel(20, 15);
  // Between two wall particles of the first layer, 0.01 below the plane y = 0: farther than dx/2
  // from every wall particle, so only the plane finds it.
  const std::size_t fluid = at(p, 0.95, 0.05);
  p.positions[3 * fluid] = 1.0;
  p.positions[3 * fluid + 1] = -0.01;
  HealthContext c = context(20);
  EXPECT_EQ(find_wall_penetration(p, c).count, 0u);
  HealthContext::Surface s;
  s.region = "bottom";
  s.surface.point = {0, 0, 0};
  s.surface.inward_normal = {0, 1, 0};
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kinds[i] == ParticleKind::kWall) s.wall_ids.push_back(p.ids[i]);
  }
  c.surfaces.push_back(s);
  const PenetrationResult r = find_wall_penetration(p, c);
  EXPECT_EQ(r.count, 1u);
  EXPECT_EQ(r.worst.id, p.ids[fluid]);
  EXPECT_NEAR(r.worst.value, 0.01, 1e-12);
  // Far from the region's wall particles the plane does not count (a finite wall's plane).
  p.positions[3 * fluid + 1] = -5.0;
  EXPECT_EQ(find_wall_penetration(p, c).count, 0u);
  // A circle counts everywhere inside it.
  c.surfaces[0].surface.radius = 0.3;
  c.surfaces[0].surface.point = {1.0, -5.0, 0};
  const PenetrationResult in_circle = find_wall_penetration(p, c);
  EXPECT_EQ(in_circle.count, 1u);
  EXPECT_NEAR(in_circle.worst.value, 0.3, 1e-12);
}

TEST(RunHealth, RemovedBlockIsAHole) {
  const ParticleState full = channel(30, 30);
  // Remove the fluid particles in a 0.8 x 0.8 block (8 x 8 particles) in the middle.
  ParticleState p;
  for (std::size_t i = 0; i < full.size(); ++i) {
    const double x = full.positions[3 * i], y = full.positions[3 * i + 1];
    if (x > 1.1 && x < 1.9 && y > 1.1 && y < 1.9) continue;
    add(p, x, y, full.kinds[i]);
  }
  ASSERT_EQ(p.size(), full.size() - 64);
  const HoleResult holes = find_holes(p, context(30));
  EXPECT_EQ(holes.count, 1u);
  EXPECT_GE(holes.largest, 1u);
  EXPECT_NEAR(holes.centre[0], 1.5, 0.3);
  EXPECT_NEAR(holes.centre[1], 1.5, 0.3);
  // A block smaller than a cell of size h leaves no cell empty.
  EXPECT_EQ(find_holes(p, context(30, 0.9)).count, 0u);
}

TEST(RunHealth, VoidOpenToTheOutsideIsNoHole) {
  const ParticleState full = channel(30, 30);
  ParticleState p;  // a notch cut from the free surface at the top
  for (std::size_t i = 0; i < full.size(); ++i) {
    const double x = full.positions[3 * i], y = full.positions[3 * i + 1];
    if (x > 1.1 && x < 1.9 && y > 2.1) continue;
    add(p, x, y, full.kinds[i]);
  }
  EXPECT_EQ(find_holes(p, context(30)).count, 0u);
}

TEST(RunHealth, DensityDeviationIsExact) {
  ParticleState p;
  add(p, 0.05, 0.05, ParticleKind::kFluid, 1.02);
  add(p, 0.15, 0.05, ParticleKind::kFluid, 0.97);
  add(p, 0.25, 0.05, ParticleKind::kFluid, 1.0);
  add(p, 0.35, 0.05, ParticleKind::kWall, 3.0);  // walls are not counted
  const DensityResult r = density_deviation(p, 1.0);
  EXPECT_EQ(r.fluid, 3u);
  EXPECT_NEAR(r.max, 0.03, 1e-12);
  EXPECT_EQ(r.max_id, 1u);
  EXPECT_NEAR(r.rms, std::sqrt((0.02 * 0.02 + 0.03 * 0.03) / 3), 1e-12);
  const DensityResult scaled = density_deviation(p, 2.0);
  EXPECT_NEAR(scaled.max, 0.515, 1e-12);
}

TEST(RunHealth, HealthCheckWarnsAndBudgetsSpecies) {
  HealthContext c = context(20);
  c.species_known = true;
  c.species.push_back({"A", true, {}, {}});                   // nothing changes it
  c.species.push_back({"B", true, {"decay"}, {}});            // a reaction
  c.species.push_back({"C", true, {}, {"left: dirichlet"}});  // a boundary
  c.species.push_back({"D", false, {}, {}});                  // deterministic, conserved
  HealthCheck check(c);
  ParticleState p = channel(20, 15);
  const auto columns = [&](double a, double b, double cc, double d) {
    std::vector<SpeciesColumn> s = {{"A", {}}, {"B", {}}, {"C", {}}, {"D", {}}, {"E", {}}};
    for (std::size_t i = 0; i < p.size(); ++i) {
      const bool first = i == 0;
      s[0].values.push_back(first ? a : 0);
      s[1].values.push_back(first ? b : 0);
      s[2].values.push_back(first ? cc : 0);
      s[3].values.push_back(first ? d : 0);
      s[4].values.push_back(1);  // not a species of the context (an assigned one): skipped
    }
    return s;
  };
  check.add_frame(p, columns(10, 10, 10, 100), 0.0, "f0");
  EXPECT_TRUE(check.warnings().empty());
  // A fluid particle into the wall, densities off, A and D changed.
  const std::size_t fluid = at(p, 0.95, 0.05);
  p.positions[3 * fluid] = 0.55;
  p.positions[3 * fluid + 1] = -0.05;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kinds[i] == ParticleKind::kFluid) p.densities[i] = 1.2;
  }
  check.add_frame(p, columns(11, 7, 15, 100), 1.0, "f1");
  const auto budgets = check.budgets();
  ASSERT_EQ(budgets.size(), 4u);
  EXPECT_EQ(budgets[0].verdict, "conserved");
  EXPECT_TRUE(budgets[0].warning);
  EXPECT_EQ(budgets[1].verdict, "reactions");
  EXPECT_FALSE(budgets[1].warning);
  EXPECT_EQ(budgets[2].verdict, "boundaries");
  EXPECT_DOUBLE_EQ(budgets[2].last - budgets[2].first, 5.0);
  EXPECT_TRUE(budgets[3].amount);
  EXPECT_DOUBLE_EQ(budgets[3].first, 100 * kDx * kDx);  // c V with V = m / rho = dx^2 / 1
  const auto w = check.warnings();
  ASSERT_EQ(w.size(), 4u);  // penetration, density max, density RMS, species A
  EXPECT_NE(w[0].find("inside walls"), std::string::npos);
  EXPECT_NE(w[3].find("species A"), std::string::npos);
  EXPECT_EQ(check.penetration_worst.time, 1.0);
  EXPECT_EQ(check.penetration_worst.frame, "f1");
  EXPECT_NEAR(check.density_worst.value, 0.2, 1e-12);
  const nlohmann::json j = check.report();
  EXPECT_EQ(j["penetration"]["max"], 1);
  EXPECT_EQ(j["warnings"].size(), 4u);
}

TEST(RunHealth, ContextFromSceneListsWhatChangesEachSpecies) {
  const Scene s = parse_scene(test::kBaseScene, "scene.yaml");
  const HealthContext c = health_context(s);
  EXPECT_TRUE(c.from_scene);
  EXPECT_DOUBLE_EQ(c.spacing, 0.25);
  EXPECT_DOUBLE_EQ(c.support, 0.45);
  ASSERT_EQ(c.species.size(), 2u);
  EXPECT_EQ(c.species[0].reactions.size(), 1u);  // A -> 0
  ASSERT_EQ(c.species[0].boundaries.size(), 1u);
  EXPECT_EQ(c.species[0].boundaries[0], "left: dirichlet");
  EXPECT_TRUE(c.species[1].reactions.empty());
  EXPECT_TRUE(c.species[1].boundaries.empty());
  EXPECT_FALSE(c.species[1].stochastic);
}

}  // namespace
}  // namespace sadr::orchestrator
