// SPDX-License-Identifier: MIT
// The model library's one set of range checks (sadr/model/): what each check finds, by field.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "sadr/common/status.hpp"
#include "sadr/model/chemistry.hpp"

namespace sadr::model {
namespace {

std::vector<std::string> fields(const Problems& p) {
  std::vector<std::string> out;
  for (const auto& q : p.list()) out.push_back(q.field);
  return out;
}

Reaction decay() {
  Reaction r;
  r.name = "decay";
  r.reactants = {{"A", 1}};
  r.rate = 0.5;
  return r;
}

TEST(ModelChecks, ProblemNamesFieldValueAndAllowed) {
  Problems p;
  p.set_prefix("reactions[3]");
  p.finite_nonneg("rate", -2.0);
  ASSERT_EQ(p.list().size(), 1u);
  EXPECT_EQ(p.list()[0], (Problem{"reactions[3].rate", "-2", "finite and >= 0"}));
  EXPECT_EQ(p.text(), "reactions[3].rate = -2 (allowed: finite and >= 0)");
  try {
    p.throw_if_any("init.model");
    FAIL() << "a problem must throw";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(std::string(e.what()),
              "init.model: reactions[3].rate = -2 (allowed: finite and >= 0)");
    ASSERT_EQ(e.details().size(), 1u);
    EXPECT_EQ(e.details()[0].first, "reactions[3].rate");
  }
  Problems none;
  EXPECT_NO_THROW(none.throw_if_any());
}

TEST(ModelChecks, AValidReactionHasNoProblem) {
  Problems p;
  check(decay(), p);
  EXPECT_TRUE(p.empty()) << p.text();
}

TEST(ModelChecks, RateMustBeFiniteAndNonNegative) {
  for (double bad : {-1.0, std::nan(""), HUGE_VAL}) {
    Reaction r = decay();
    r.rate = bad;
    Problems p;
    check(r, p);
    EXPECT_EQ(fields(p), std::vector<std::string>{"rate"}) << bad;
  }
}

TEST(ModelChecks, CountsAtLeastOneAndMassActionOrderAtMostTwo) {
  Reaction r = decay();
  r.reactants = {{"A", 2}, {"B", 1}};
  r.products = {{"C", 0}};
  Problems p;
  check(r, p);
  EXPECT_EQ(fields(p), (std::vector<std::string>{"products[0].count", "reactants"}));
  EXPECT_NE(p.text().find("order 3 is not allowed"), std::string::npos) << p.text();
  // A law takes any order.
  r.products = {{"C", 1}};
  r.law = rate_law::Definition{};
  Problems with_law;
  check(r, with_law);
  EXPECT_TRUE(with_law.empty()) << with_law.text();
}

TEST(ModelChecks, BoundaryFluxNeedsALawAndOneFiniteAreaPerSite) {
  Reaction r = decay();
  r.boundary_particles = {4, 5};
  r.boundary_areas = {0.1, -0.2, 0.3};
  Problems p;
  check(r, p);
  EXPECT_EQ(fields(p),
            (std::vector<std::string>{"boundary_areas", "boundary_areas", "boundary_areas[1]"}));
}

TEST(ModelChecks, SpeciesDiffusivityAndBoundaryValues) {
  Species s;
  s.name = "A";
  s.diffusivity = -0.1;
  s.boundaries = {{"wall", BoundaryCondition::kDirichlet, -1.0},
                  {"wall", BoundaryCondition::kNeumann, -1.0},  // outward flux: allowed
                  {"wall", BoundaryCondition::kNeumann, std::nan("")},
                  {"inlet", BoundaryCondition::kInflow, -3.0},
                  {"wall", BoundaryCondition::kFree, -5.0}};  // value unused
  Problems p;
  check(s, p);
  EXPECT_EQ(fields(p), (std::vector<std::string>{"diffusivity", "boundaries[0].value",
                                                 "boundaries[2].value", "boundaries[3].value"}));
}

TEST(ModelChecks, SsaRegularization) {
  Problems p;
  check(SsaSettings{JumpConvention::kVolume, -0.01}, p);
  EXPECT_EQ(fields(p), std::vector<std::string>{"regularization"});
  EXPECT_EQ(to_string(JumpConvention::kSymmetric), "symmetric");
  EXPECT_EQ(to_string(BoundaryCondition::kInflow), "inflow");
}

}  // namespace
}  // namespace sadr::model
