// SPDX-License-Identifier: MIT
// The inputs of hybrid reactions and laws of t in the SSA (NsmSolver::set_inputs,
// docs/method.md section 4c): a law reading a frozen (deterministic) species and t
// sees the values of the last set_inputs; wrong inputs are refused with the field
// and value; a snapshot keeps them, so a restored run continues bit-identically.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "sadr/common/status.hpp"
#include "sadr/ssa/nsm_solver.hpp"
#include "ssa_test_support.hpp"

namespace sadr::ssa {
namespace {

/// Four voxels of V = 2, no diffusion; 0 -> A at k B exp(-t) (B frozen), A -> 0 at 1.
Model model() {
  Model m;
  m.species = {{"A", 0.0}};
  m.frozen_species = {"B"};
  Reaction birth;
  birth.def.name = "birth";
  birth.products = {{0, 1}};
  rate_law::Definition d;
  d.type = rate_law::Type::kExpression;
  d.expression = "k*B*exp(-t)";
  d.parameters = {{"k", 3.0}};
  birth.def.law = d;
  Reaction death;
  death.def.name = "death";
  death.reactants = {{0, 1}};
  death.def.rate = 1.0;
  m.reactions = {birth, death};
  m.box = testing::make_box(1, 4.0, false);
  m.smoothing_length = 0.5;
  return m;
}

ParticleState voxels() {
  ParticleState p = testing::make_lattice(1, 4, 1.0);
  for (auto& mass : p.masses) mass = 2.0;
  return p;
}

TEST(HybridInputs, ExternalLawsSeeTheLastInputs) {
  NsmSolver s(model(), 3);
  s.update_graph(voxels());
  EXPECT_TRUE(s.state().reactions().has_external_laws());
  EXPECT_DOUBLE_EQ(s.voxel_rate(0), 0.0);  // B = 0 until the first inputs
  s.set_inputs(0.5, std::vector<double>{1.0, 2.0, 0.0, 4.0});
  // a = V k B exp(-t), V = 2 (no A yet).
  EXPECT_DOUBLE_EQ(s.voxel_rate(0), 2 * 3.0 * 1.0 * std::exp(-0.5));
  EXPECT_DOUBLE_EQ(s.voxel_rate(1), 2 * 3.0 * 2.0 * std::exp(-0.5));
  EXPECT_DOUBLE_EQ(s.voxel_rate(2), 0.0);
  EXPECT_DOUBLE_EQ(s.voxel_rate(3), 2 * 3.0 * 4.0 * std::exp(-0.5));
}

TEST(HybridInputs, WrongInputsAreRefusedWithFieldAndValue) {
  NsmSolver s(model(), 3);
  s.update_graph(voxels());
  auto message = [&](std::vector<double> f, double t) {
    try {
      s.set_inputs(t, f);
    } catch (const InvalidArgument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({1, 2, 3}, 0).find("3 values, expected 4 (1 species x 4 voxels)"),
            std::string::npos);
  EXPECT_NE(message({1, -2, 3, 4}, 0).find("frozen concentration of 'B' in voxel 1 = -2"),
            std::string::npos);
  EXPECT_NE(message({1, NAN, 3, 4}, 0).find("allowed: finite and >= 0"), std::string::npos);
  EXPECT_NE(message({1, 2, 3, 4}, INFINITY).find("input time"), std::string::npos);
}

TEST(HybridInputs, ARestoredRunContinuesBitIdentically) {
  auto stage = [](NsmSolver& s, int k) {
    const double b = 1.0 + 0.5 * k;
    s.set_inputs(s.time(), std::vector<double>{b, 2 * b, 3 * b, 4 * b});
    s.advance(0.25 * (k + 1));
  };
  NsmSolver a(model(), 11);
  a.update_graph(voxels());
  for (int k = 0; k < 4; ++k) stage(a, k);
  const std::string blob = a.save();
  NsmSolver b(model(), 99);
  b.update_graph(voxels());
  b.restore(blob);
  EXPECT_EQ(b.state().frozen(), a.state().frozen());
  for (int k = 4; k < 12; ++k) {
    stage(a, k);
    stage(b, k);
  }
  EXPECT_GT(a.events(), 0u);
  EXPECT_EQ(a.save(), b.save());
}

}  // namespace
}  // namespace sadr::ssa
