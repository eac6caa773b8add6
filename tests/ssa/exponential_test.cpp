// SPDX-License-Identifier: MIT
// The ziggurat Exp(1) sampler of the NSM (src/exponential.hpp): tables (equal
// layer areas), and the distribution: Kolmogorov-Smirnov over 1e6 draws, mean,
// variance and the frequency of the tail beyond r. Four comparisons, Bonferroni,
// family-wise false-failure rate 1e-4 (z* = 4.22; KS critical value
// sqrt(-ln(alpha/2)/2) with alpha = 2.5e-5 per comparison).
#include "exponential.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "ssa_test_support.hpp"

namespace sadr::ssa {
namespace {

TEST(Ziggurat, LayersHaveEqualAreas) {
  const detail::ZigguratTables& t = detail::ziggurat_tables();
  const double v = t.x[1] * std::exp(-t.x[1]) + std::exp(-t.x[1]);  // base: box + tail
  EXPECT_NEAR(t.x[0] * std::exp(-t.x[1]), v, 1e-15);
  for (int i = 1; i < 256; ++i) {
    ASSERT_GT(t.x[i], t.x[i + 1]) << i;
    EXPECT_NEAR(t.x[i] * (std::exp(-t.x[i + 1]) - std::exp(-t.x[i])), v, 1e-9 * v) << i;
  }
}

TEST(Ziggurat, DrawsAreExponential) {
  const int n = 1000000;
  rng::Xoshiro256 gen(2024, 7);
  std::vector<double> x(n);
  double sum = 0, sum2 = 0;
  int tail = 0;
  const double r = detail::ziggurat_tables().x[1];
  for (double& v : x) {
    v = detail::exponential(gen);
    ASSERT_TRUE(v > 0 && std::isfinite(v));
    sum += v;
    sum2 += v * v;
    tail += v > r ? 1 : 0;
  }
  const double alpha = 1e-4 / 4;
  const double z = testing::z_star(1e-4, 4);
  const double mean = sum / n, var = sum2 / n - mean * mean;
  EXPECT_LT(std::abs(mean - 1.0) / std::sqrt(1.0 / n), z);  // Var Exp(1) = 1
  // Var of the sample variance ~ (mu4 - sigma^4)/n = (9 - 1)/n.
  EXPECT_LT(std::abs(var - 1.0) / std::sqrt(8.0 / n), z);
  const double p = std::exp(-r);
  EXPECT_LT(std::abs(tail - n * p) / std::sqrt(n * p * (1 - p)), z) << tail;
  std::sort(x.begin(), x.end());
  double d = 0;
  for (int k = 0; k < n; ++k) {
    const double f = 1.0 - std::exp(-x[k]);
    d = std::max({d, std::abs(f - static_cast<double>(k) / n),
                  std::abs(f - static_cast<double>(k + 1) / n)});
  }
  EXPECT_LT(d * std::sqrt(static_cast<double>(n)), std::sqrt(-0.5 * std::log(alpha / 2))) << d;
}

}  // namespace
}  // namespace sadr::ssa
