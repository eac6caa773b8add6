// SPDX-License-Identifier: MIT
// Unit: kernel normalisation, F = -(1/r) dW/dr, gradient antisymmetry, Tait EOS.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sadr/common/status.hpp"
#include "sadr/fluid/kernel.hpp"
#include "sadr/fluid/tait_eos.hpp"

namespace sadr::fluid {
namespace {

// Integral of W over R^d by the radial rule with 20000 midpoints (error ~1e-9).
double integral(const Kernel& k) {
  const int n = 20000;
  const double h = k.support(), dr = h / n;
  double s = 0;
  for (int m = 0; m < n; ++m) {
    const double r = (m + 0.5) * dr;
    const double shell = k.dimension() == 1   ? 2.0
                         : k.dimension() == 2 ? 2 * std::numbers::pi * r
                                              : 4 * std::numbers::pi * r * r;
    s += k.w(r) * shell * dr;
  }
  return s;
}

class KernelParam : public ::testing::TestWithParam<std::tuple<KernelType, int>> {};

TEST_P(KernelParam, IntegratesToOne) {
  const auto [type, dim] = GetParam();
  for (double h : {0.3, 1.0, 2.7}) {
    EXPECT_NEAR(integral(Kernel(type, dim, h)), 1.0, 1e-7) << "dim " << dim << " h " << h;
  }
}

TEST_P(KernelParam, FIsMinusDerivativeOverR) {
  const auto [type, dim] = GetParam();
  const Kernel k(type, dim, 1.3);
  for (double r : {0.05, 0.3, 0.7, 1.2}) {
    const double e = 1e-6;
    const double dwdr = (k.w(r + e) - k.w(r - e)) / (2 * e);
    EXPECT_NEAR(k.f(r), -dwdr / r, 1e-6 * std::max(1.0, k.f(r)));
    EXPECT_GE(k.f(r), 0.0);
  }
  EXPECT_EQ(k.w(1.3), 0.0);
  EXPECT_EQ(k.f(1.31), 0.0);
}

// grad_i W_ij = dW/dr x_ij / r = -F x_ij: exactly antisymmetric under i <-> j.
TEST_P(KernelParam, GradientAntisymmetric) {
  const auto [type, dim] = GetParam();
  const Kernel k(type, dim, 1.0);
  const double xi[3] = {0.1, 0.2, 0.3}, xj[3] = {0.4, -0.1, 0.5};
  double gij[3], gji[3], r2 = 0;
  for (int a = 0; a < 3; ++a) r2 += (xi[a] - xj[a]) * (xi[a] - xj[a]);
  const double r = std::sqrt(r2);
  for (int a = 0; a < 3; ++a) {
    gij[a] = -k.f(r) * (xi[a] - xj[a]);
    gji[a] = -k.f(r) * (xj[a] - xi[a]);
    EXPECT_EQ(gij[a], -gji[a]);
  }
}

INSTANTIATE_TEST_SUITE_P(
    All, KernelParam,
    ::testing::Combine(::testing::Values(KernelType::kLucy, KernelType::kWendlandC2),
                       ::testing::Values(1, 2, 3)),
    [](const ::testing::TestParamInfo<std::tuple<KernelType, int>>& param_info) {
      return std::string(std::get<0>(param_info.param) == KernelType::kLucy ? "lucy" : "wendland") +
             std::to_string(std::get<1>(param_info.param)) + "d";
    });

TEST(Kernel, LucyConstantsMatchSpec) {
  EXPECT_DOUBLE_EQ(Kernel(KernelType::kLucy, 1, 2.0).w0(), 5.0 / 8.0);
  EXPECT_DOUBLE_EQ(Kernel(KernelType::kLucy, 2, 2.0).w0(), 5.0 / (std::numbers::pi * 4.0));
  EXPECT_DOUBLE_EQ(Kernel(KernelType::kLucy, 3, 2.0).w0(), 105.0 / (16.0 * std::numbers::pi * 8.0));
}

TEST(Kernel, ParseNames) {
  EXPECT_EQ(parse_kernel("lucy"), KernelType::kLucy);
  EXPECT_EQ(parse_kernel("wendland_c2"), KernelType::kWendlandC2);
  try {
    (void)parse_kernel("cubic");
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("lucy, wendland_c2"), std::string::npos);
  }
}

TEST(TaitEos, PressureAndStiffness) {
  const TaitEos eos(1000.0, 10.0);
  EXPECT_DOUBLE_EQ(eos.pressure(1000.0), 0.0);
  EXPECT_NEAR(eos.pressure(1010.0), 1000.0 * 100.0 / 7.0 * (std::pow(1.01, 7) - 1.0), 1e-9);
  // dP/drho at rho0 = c0^2
  EXPECT_NEAR((eos.pressure(1000.0 + 1e-4) - eos.pressure(1000.0 - 1e-4)) / 2e-4, 100.0, 1e-5);
}

}  // namespace
}  // namespace sadr::fluid
