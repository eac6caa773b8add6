// SPDX-License-Identifier: MIT
// Input validation (errors name field and value), the rate conversion table,
// and solver-level bookkeeping that needs no statistics.
#include "sadr/ssa/model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "sadr/common/mass_action.hpp"
#include "sadr/common/status.hpp"
#include "sadr/ssa/nsm_solver.hpp"
#include "ssa_test_support.hpp"

namespace sadr::ssa {
namespace {

using testing::message_of;

Model good_model() {
  Model m = testing::diffusion_model(testing::make_box(2, 4.0, false), 1.5, 1.0);
  m.species.push_back({"B", 0.5});
  m.reactions.push_back({"bind", {{0, 1}, {1, 1}}, {{0, 2}}, 1.0, {}, {}});
  return m;
}

TEST(ModelValidate, AcceptsAGoodModel) {
  EXPECT_NO_THROW(good_model().validate());
}

TEST(ModelValidate, BadValuesNameFieldAndValue) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  {
    Model m = good_model();
    m.reactions[0].def.rate = -2.5;
    const auto msg = message_of([&] { m.validate(); });
    EXPECT_NE(msg.find("reactions[0] 'bind'.rate"), std::string::npos) << msg;
    EXPECT_NE(msg.find("-2.5"), std::string::npos) << msg;
  }
  {
    Model m = good_model();
    m.reactions[0].def.rate = nan;
    EXPECT_NE(message_of([&] { m.validate(); }).find("nan"), std::string::npos);
  }
  {
    Model m = good_model();
    m.species[1].def.diffusivity = std::numeric_limits<double>::infinity();
    const auto msg = message_of([&] { m.validate(); });
    EXPECT_NE(msg.find("species[1].diffusivity"), std::string::npos) << msg;
    EXPECT_NE(msg.find("inf"), std::string::npos) << msg;
  }
  {
    Model m = good_model();
    m.smoothing_length = 0;
    m.reactions[0].reactants[0].first = 7;  // two problems, both reported
    const auto msg = message_of([&] { m.validate(); });
    EXPECT_NE(msg.find("smoothing_length = 0"), std::string::npos) << msg;
    EXPECT_NE(msg.find("reactants[0].species = 7"), std::string::npos) << msg;
  }
  {
    Model m = good_model();
    m.reactions[0].reactants = {{0, 3}};
    EXPECT_NE(message_of([&] { m.validate(); }).find("order 3 is not allowed"), std::string::npos);
  }
  {
    Model m = good_model();
    m.box.periodic[0] = true;
    m.smoothing_length = 2.5;  // > L/2
    EXPECT_NE(message_of([&] { m.validate(); }).find("half the periodic box"), std::string::npos);
  }
  {
    Model m = good_model();
    m.neumann.push_back({0, -1.0});
    EXPECT_NE(message_of([&] { m.validate(); }).find("neumann[0].flux = -1"), std::string::npos);
  }
}

TEST(ModelValidate, UnknownSpeciesNameListsKnownOnes) {
  const Model m = good_model();
  EXPECT_EQ(m.species_index("B"), 1);
  const auto msg = message_of([&] { (void)m.species_index("C"); });
  EXPECT_NE(msg.find("'C'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("known: A, B"), std::string::npos) << msg;
}

TEST(SolverInput, BadParticlesNameFieldIndexAndValue) {
  NsmSolver s(good_model(), 1);
  ParticleState p = testing::make_lattice(2, 4, 1.0);
  p.masses[5] = -1.0;
  EXPECT_NE(message_of([&] { s.update_graph(p); }).find("particle 5: mass = -1"),
            std::string::npos);
  p = testing::make_lattice(2, 4, 1.0);
  p.densities[2] = 0;
  EXPECT_NE(message_of([&] { s.update_graph(p); }).find("particle 2: density = 0"),
            std::string::npos);
  p = testing::make_lattice(2, 4, 1.0);
  p.positions[3 * 3 + 1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(message_of([&] { s.update_graph(p); }).find("particle 3: position[1] = nan"),
            std::string::npos);
  p = testing::make_lattice(2, 4, 1.0);
  p.positions[3 * 1] = 4.5;  // walled box [0, 4]
  const auto msg = message_of([&] { s.update_graph(p); });
  EXPECT_NE(msg.find("particle 1: position[0] = 4.5 is outside"), std::string::npos) << msg;
  p = testing::make_lattice(2, 4, 1.0);
  ASSERT_NO_THROW(s.update_graph(p));
  std::vector<std::int64_t> c(16, 1);
  c[4] = -3;
  EXPECT_NE(message_of([&] { s.set_counts(0, c); }).find("counts[4] = -3"), std::string::npos);
  EXPECT_NE(message_of([&] { s.advance(-1.0); }).find("t_end = -1"), std::string::npos);
}

// The one documented conversion (common/mass_action.hpp), and the law both services use.
TEST(RateConversion, TableOfSpecSection4) {
  const double k = 0.3, v = 2.5;
  EXPECT_DOUBLE_EQ(mass_action::voxel_constant(k, 0, v), k * v);
  EXPECT_DOUBLE_EQ(mass_action::voxel_constant(k, 1, v), k);
  EXPECT_DOUBLE_EQ(mass_action::voxel_constant(k, 2, v), k / v);
  EXPECT_THROW((void)mass_action::voxel_constant(k, 3, v), InvalidArgument);
  EXPECT_DOUBLE_EQ(mass_action::combinations(7, 1), 7.0);
  EXPECT_DOUBLE_EQ(mass_action::combinations(7, 2), 21.0);
  EXPECT_DOUBLE_EQ(mass_action::combinations(1, 2), 0.0);
}

// The SSA's propensity per volume tends to the deterministic rate of the same
// law (fluid_service's SpeciesTransport) as X = C V grows: exactly for A + B and
// for order 0, with relative difference 1/X for A + A (a factor 2 off would fail).
TEST(RateConversion, StochasticPropensityPerVolumeTendsToTheDeterministicRate) {
  const double k = 0.3, v = 2.0;
  const std::int64_t xa = 1000000, xb = 400000;
  const double ca = static_cast<double>(xa) / v, cb = static_cast<double>(xb) / v;
  using namespace mass_action;
  const double ab_det = k * concentration_term(ca, 1, inverse_factorial(1)) *
                        concentration_term(cb, 1, inverse_factorial(1));
  const double ab_ssa = voxel_constant(k, 2, v) * combinations(xa, 1) * combinations(xb, 1);
  EXPECT_DOUBLE_EQ(ab_ssa / v, ab_det);
  const double aa_det = k * concentration_term(ca, 2, inverse_factorial(2));  // k C^2 / 2
  const double aa_ssa = voxel_constant(k, 2, v) * combinations(xa, 2);
  EXPECT_NEAR(aa_ssa / v / aa_det, 1.0 - 1.0 / static_cast<double>(xa), 1e-12);
  EXPECT_DOUBLE_EQ(voxel_constant(k, 0, v) / v, k);
  EXPECT_DOUBLE_EQ(inverse_factorial(2), 0.5);
}

// Propensities in a voxel of volume V = 2: A + B -> C is (k/V) X_A X_B (not k/(2V));
// A + A -> B is (k/V) X(X-1)/2; 0 -> A is k V.
TEST(RateConversion, VoxelPropensitiesUseTheVoxelVolume) {
  Model m = testing::diffusion_model(testing::make_box(1, 4.0, false), 0.5, 0.0);
  m.species = {{"A", 0}, {"B", 0}, {"C", 0}};
  m.reactions.push_back({"ab", {{0, 1}, {1, 1}}, {{2, 1}}, 0.4, {}, {}});
  NsmSolver s1(m, 1);
  ParticleState p = testing::make_lattice(1, 1, 1.0);
  p.masses[0] = 2.0;  // V = 2
  s1.update_graph(p);
  const std::vector<std::int64_t> a = {6}, b = {5};
  s1.set_counts(0, a);
  s1.set_counts(1, b);
  EXPECT_DOUBLE_EQ(s1.voxel_rate(0), 0.4 / 2.0 * 6 * 5);
  m.reactions = {{"aa", {{0, 2}}, {{1, 1}}, 0.4, {}, {}}, {"birth", {}, {{2, 1}}, 1.5, {}, {}}};
  NsmSolver s2(m, 1);
  s2.update_graph(p);
  s2.set_counts(0, a);
  EXPECT_DOUBLE_EQ(s2.voxel_rate(0), 0.4 / 2.0 * 15 + 1.5 * 2.0);
}

TEST(ReactionRestriction, KindsAndVoxels) {
  Model m = testing::diffusion_model(testing::make_box(1, 4.0, false), 0.5, 0.0);
  m.reactions.push_back({"birth_fluid", {}, {{0, 1}}, 1.0, {}, {}});
  m.reactions.push_back({"birth_wall_v3", {}, {{0, 1}}, 10.0, {ParticleKind::kWall}, {3}});
  NsmSolver s(m, 1);
  ParticleState p = testing::make_lattice(1, 4, 1.0);
  p.kinds[0] = p.kinds[3] = ParticleKind::kWall;
  s.update_graph(p);
  EXPECT_DOUBLE_EQ(s.voxel_rate(0), 0.0);
  EXPECT_DOUBLE_EQ(s.voxel_rate(1), 1.0);
  EXPECT_DOUBLE_EQ(s.voxel_rate(3), 10.0);
}

TEST(UpdateGraph, NoRebuildWhenParticlesUnchanged) {
  Model m = testing::diffusion_model(testing::make_box(2, 6.0, true), 1.6, 1.0);
  const ParticleState p = testing::make_lattice(2, 6, 1.0, 0.2, 0.1, 4);
  NsmSolver a(m, 9), b(m, 9);
  EXPECT_TRUE(a.update_graph(p));
  EXPECT_TRUE(b.update_graph(p));
  std::vector<std::int64_t> c(36, 0);
  c[7] = 50;
  a.set_counts(0, c);
  b.set_counts(0, c);
  a.advance(0.5);
  b.advance(0.5);
  EXPECT_FALSE(b.update_graph(p));  // no-op: same inputs
  a.advance(1.0);
  b.advance(1.0);
  EXPECT_EQ(a.events(), b.events());
  EXPECT_TRUE(std::equal(a.counts(0).begin(), a.counts(0).end(), b.counts(0).begin()));
  ParticleState moved = p;
  moved.positions[0] += 0.01;
  EXPECT_TRUE(b.update_graph(moved));
}

}  // namespace
}  // namespace sadr::ssa
