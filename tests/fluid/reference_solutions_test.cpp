// SPDX-License-Identifier: MIT
// Unit: the C++ ports of the reference solutions reproduce the spot values of refs/README.md.
#include <gtest/gtest.h>

#include "reference_solutions.hpp"

namespace sadr::fluid::test {
namespace {

TEST(References, StepSpotValues) {
  EXPECT_NEAR(step_neumann(5.0, 100.0, 0.05), 0.0569231490, 1e-9);
  EXPECT_NEAR(1.0 - step_neumann(-5.0, 100.0, 0.5), 0.3085375387,
              1e-6);  // neu vs inf differ by 3e-7
  EXPECT_NEAR(step_neumann(0.0, 37.0, 0.05), 0.5, 1e-12);
}

TEST(References, DirichletSpotValues) {
  EXPECT_NEAR(dirichlet_exact(50, 100), 0.0723017597, 1e-9);
  EXPECT_NEAR(dirichlet_exact(50, 500), 0.4057072745, 1e-9);
  EXPECT_NEAR(dirichlet_exact(50, 1000), 0.4860338622, 1e-9);
  EXPECT_NEAR(dirichlet_exact(50, 2500), 0.4999546194, 1e-9);
}

TEST(References, NeumannSpotValues) {
  EXPECT_NEAR(neumann_exact(0, 100), 0.2219783106, 1e-9);
  EXPECT_NEAR(neumann_exact(0, 1000), 0.6880302286, 1e-9);
  EXPECT_NEAR(neumann_exact(0, 5000), 0.9931563862, 1e-9);
  EXPECT_NEAR(neumann_exact(50, 1000), 0.2794276505, 1e-9);
}

TEST(References, PoiseuilleSpotValues) {
  const double umax = 2.5e-5;
  const double t[] = {0.0225, 0.045, 0.1125, 0.225, 1.0};
  const double want[] = {0.1786190006, 0.3387656446, 0.6599931076, 0.8879841327, 0.9999466};
  for (int k = 0; k < 5; ++k) EXPECT_NEAR(poiseuille_exact(0.5e-3, t[k]) / umax, want[k], 1e-7);
  EXPECT_NEAR(poiseuille_exact(0.3e-3, 0.0), 0.0, 1e-12);
}

TEST(References, ScaledNormsOfKnownVectors) {
  const auto [l2, linf] = scaled_norms({1, 2, 3}, {1, 2, 5}, {1, 1, 2}, 2.0);
  EXPECT_NEAR(l2, std::sqrt(8.0 / 4.0) / 2.0, 1e-15);
  EXPECT_NEAR(linf, 1.0, 1e-15);
}

}  // namespace
}  // namespace sadr::fluid::test
