// SPDX-License-Identifier: MIT
// Unit: rate_law::RateLaw (common/rate_law.hpp): values of each law, the species
// a law reads (its propensity dependencies), and the load-time refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "sadr/common/rate_law.hpp"
#include "sadr/common/status.hpp"

namespace sadr::rate_law {
namespace {

const std::vector<std::string> kNames = {"S", "E", "P", "A"};

Definition mm() {
  Definition d;
  d.type = Type::kMichaelisMenten;
  d.kcat = 2.5;
  d.km = 0.4;
  d.substrate = std::string("S");
  d.catalyst = std::string("E");
  d.origin = std::string("scene.yaml:7");
  return d;
}

Definition expr(std::string text) {
  Definition d;
  d.type = Type::kExpression;
  d.expression = std::move(text);
  d.parameters = {{"kcat", 2.5}, {"Km", 0.4}};
  d.origin = std::string("scene.yaml:9");
  return d;
}

std::string error_of(const Definition& d, bool allow_time = true) {
  try {
    const RateLaw law(d, kNames, allow_time);
    law.check_admissible({});
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "";
}

TEST(RateLaw, MichaelisMentenValueAndDependencies) {
  const RateLaw law(mm(), kNames);
  ASSERT_EQ(law.species(), (std::vector<int>{0, 1}));  // S, E in index order
  const double c[2] = {0.6, 3.0};                      // S, E
  EXPECT_DOUBLE_EQ(law.density(c, 0), 2.5 * 3.0 * 0.6 / (0.4 + 0.6));
}

TEST(RateLaw, HillValue) {
  Definition d;
  d.type = Type::kHill;
  d.vmax = 3;
  d.half = 2;
  d.n = 2.5;
  d.of = std::string("A");
  const RateLaw law(d, kNames);
  ASSERT_EQ(law.species(), (std::vector<int>{3}));
  const double c[1] = {1.5};
  EXPECT_DOUBLE_EQ(law.density(c, 0),
                   3 * std::pow(1.5, 2.5) / (std::pow(2.0, 2.5) + std::pow(1.5, 2.5)));
}

TEST(RateLaw, ExpressionReadsOnlyTheSpeciesItUsesAndEqualsTheBuiltIn) {
  const RateLaw e(expr("kcat*E*S/(Km+S)"), kNames);
  const RateLaw m(mm(), kNames);
  ASSERT_EQ(e.species(), (std::vector<int>{0, 1}));
  EXPECT_FALSE(e.uses_time());
  for (double s : {0.0, 1e-3, 0.7, 12.0}) {
    for (double en : {0.0, 1.0, 4.5}) {
      const double c[2] = {s, en};
      EXPECT_EQ(e.density(c, 0), m.density(c, 0)) << s << " " << en;
    }
  }
  const RateLaw t(expr("2*t + P"), kNames);
  EXPECT_TRUE(t.uses_time());
  const double c[1] = {1.0};
  EXPECT_DOUBLE_EQ(t.density(c, 3.0), 7.0);
}

TEST(RateLaw, CopiesEvaluateIndependently) {
  const RateLaw a(expr("kcat*S"), kNames);
  RateLaw b = a;  // re-parsed: its own bound variables
  const double x[1] = {2.0}, y[1] = {4.0};
  EXPECT_DOUBLE_EQ(a.density(x, 0), 5.0);
  EXPECT_DOUBLE_EQ(b.density(y, 0), 10.0);
  EXPECT_DOUBLE_EQ(a.density(x, 0), 5.0);
}

TEST(RateLaw, MassActionMatchesTheConcentrationLaw) {
  Definition d;
  d.k = 0.5;
  d.reactants = {{"A", 2}, {"S", 1}};
  const RateLaw law(d, kNames);
  ASSERT_EQ(law.species(), (std::vector<int>{0, 3}));
  const double c[2] = {3.0, 2.0};  // S, A
  EXPECT_DOUBLE_EQ(law.density(c, 0), 0.5 * 3.0 * 2.0 * 2.0 / 2.0);
}

TEST(RateLaw, DerivativeOfMichaelisMenten) {
  const RateLaw law(mm(), kNames);
  const double c[2] = {0.6, 3.0};
  const double exact = 2.5 * 3.0 * 0.4 / ((0.4 + 0.6) * (0.4 + 0.6));
  EXPECT_NEAR(law.derivative(c, 0, 0), exact, 1e-5 * exact);
}

// Each refusal names where the law was written, the law, and the problem.
TEST(RateLaw, WrongLawsAreRefusedWithOriginAndText) {
  std::string msg = error_of(expr("kcat*X*S"));
  EXPECT_NE(msg.find("scene.yaml:9"), std::string::npos) << msg;
  EXPECT_NE(msg.find("kcat*X*S"), std::string::npos) << msg;
  EXPECT_NE(msg.find("unknown symbol 'X'"), std::string::npos) << msg;

  msg = error_of(expr("kcat*(S"));
  EXPECT_NE(msg.find("scene.yaml:9"), std::string::npos) << msg;
  EXPECT_NE(msg.find("kcat*(S"), std::string::npos) << msg;

  msg = error_of(expr("kcat*(S - 1)"));  // negative below S = 1
  EXPECT_NE(msg.find("v = -2.5"), std::string::npos) << msg;
  EXPECT_NE(msg.find("S = 0"), std::string::npos) << msg;

  msg = error_of(expr("S/P"));  // 0/0 at the origin
  EXPECT_NE(msg.find("nan"), std::string::npos) << msg;

  msg = error_of(expr("kcat*S*t"), false);
  EXPECT_NE(msg.find("time t"), std::string::npos) << msg;

  Definition bad = mm();
  bad.km = 0;
  msg = error_of(bad);
  EXPECT_NE(msg.find("Km = 0"), std::string::npos) << msg;
  bad = mm();
  bad.catalyst = std::string("Q");
  msg = error_of(bad);
  EXPECT_NE(msg.find("catalyst = 'Q'"), std::string::npos) << msg;
  EXPECT_EQ(error_of(expr("")).find("empty") != std::string::npos, true);
}

}  // namespace
}  // namespace sadr::rate_law
