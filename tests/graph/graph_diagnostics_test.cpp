// SPDX-License-Identifier: MIT
// sadr::ssa::diagnose_graph on graphs whose structure is known by hand:
// components, isolated voxels (also next to walls), degrees, weight and rate
// extremes.
#include <gtest/gtest.h>

#include <cmath>

#include "sadr/ssa/graph_diagnostics.hpp"

namespace sadr::ssa {
namespace {

/// Particles at `x` on the 1D walled box [0, 1] (m = rho = 1), kinds as given.
struct Line {
  Model model;
  ParticleState p;
  Line(std::vector<double> x, double h, std::vector<ParticleKind> kinds = {}) {
    model.box.dimension = 1;
    model.box.hi = {1.0, 1.0, 1.0};
    model.smoothing_length = h;
    model.species = {{"A", 0.5}, {"B", 2.0}, {"C", 0.0}};
    p.dimension = 1;
    p.resize(x.size(), false);
    for (std::size_t i = 0; i < x.size(); ++i) {
      p.positions[3 * i] = x[i];
      p.densities[i] = 1.0;
      p.masses[i] = 0.1;
    }
    p.kinds = std::move(kinds);
  }
  GraphDiagnostics diagnose() const {
    return diagnose_graph(DiffusionGraph::build(model, p), model);
  }
};

TEST(GraphDiagnostics, ChainIsOneComponentWithEndDegreesOne) {
  const auto d = Line({0.1, 0.2, 0.3, 0.4}, 0.15).diagnose();
  EXPECT_EQ(d.voxels, 4u);
  EXPECT_EQ(d.edges, 6u);
  EXPECT_EQ(d.components, 1u);
  EXPECT_EQ(d.largest_component, 4u);
  EXPECT_EQ(d.isolated, 0u);
  EXPECT_FALSE(d.isolated_example.has_value());
  EXPECT_EQ(d.min_degree, 1u);
  EXPECT_EQ(d.max_degree, 2u);
  EXPECT_DOUBLE_EQ(d.mean_degree, 1.5);
  EXPECT_TRUE(d.isolated_warning().empty());
}

TEST(GraphDiagnostics, WeightsAndRatesAreTheExtremesOverEdgesAndDiffusingSpecies) {
  // Distances 0.1 and 0.05 (h = 0.15): two different weights; C (kappa 0) is not a rate.
  const Line line({0.1, 0.2, 0.25}, 0.15);
  const auto g = DiffusionGraph::build(line.model, line.p);
  double lo = INFINITY, hi = 0;
  for (const auto& e : g.edges) {
    const double w = e.weight;  // packed edge: no reference to the field
    lo = std::min(lo, w);
    hi = std::max(hi, w);
  }
  ASSERT_LT(lo, hi);
  const auto d = diagnose_graph(g, line.model);
  EXPECT_EQ(d.min_weight, lo);
  EXPECT_EQ(d.max_weight, hi);
  EXPECT_EQ(d.min_rate, 0.5 * lo);
  EXPECT_EQ(d.min_rate_species, "A");
  EXPECT_EQ(d.max_rate, 2.0 * hi);
  EXPECT_EQ(d.max_rate_species, "B");
}

TEST(GraphDiagnostics, FarParticleIsIsolatedAndItsOwnComponent) {
  const auto d = Line({0.1, 0.2, 0.9, 0.3}, 0.15).diagnose();
  EXPECT_EQ(d.components, 2u);
  EXPECT_EQ(d.largest_component, 3u);
  EXPECT_EQ(d.isolated, 1u);
  ASSERT_TRUE(d.isolated_example.has_value());
  EXPECT_EQ(*d.isolated_example, 2u);
  EXPECT_EQ(d.min_degree, 0u);
  const std::string w = d.isolated_warning();
  EXPECT_NE(w.find("1 of 4 fluid voxels"), std::string::npos) << w;
  EXPECT_NE(w.find("particle 2"), std::string::npos) << w;
}

TEST(GraphDiagnostics, FluidVoxelWithOnlyWallNeighboursIsIsolated) {
  // 0.5 (fluid) touches only the wall at 0.6; the wall pair 0.6-0.7 is not a fluid voxel.
  using K = ParticleKind;
  const auto d =
      Line({0.1, 0.2, 0.5, 0.6, 0.7}, 0.15, {K::kFluid, K::kFluid, K::kFluid, K::kWall, K::kWall})
          .diagnose();
  EXPECT_EQ(d.wall_voxels, 2u);
  EXPECT_EQ(d.components, 2u);
  EXPECT_EQ(d.isolated, 1u);
  EXPECT_EQ(*d.isolated_example, 2u);
  EXPECT_NE(d.isolated_warning().find("1 of 3 fluid voxels"), std::string::npos);
}

TEST(GraphDiagnostics, NoEdgesAtAll) {
  const auto d = Line({0.1, 0.5, 0.9}, 0.15).diagnose();
  EXPECT_EQ(d.edges, 0u);
  EXPECT_EQ(d.components, 3u);
  EXPECT_EQ(d.isolated, 3u);
  EXPECT_EQ(d.min_weight, 0.0);
  EXPECT_TRUE(d.min_rate_species.empty());
  EXPECT_EQ(d.lines().size(), 1u);  // no weight line without edges
}

}  // namespace
}  // namespace sadr::ssa
