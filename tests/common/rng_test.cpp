// SPDX-License-Identifier: MIT
#include "sadr/common/rng.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace sadr::rng {
namespace {

// Known-answer test from the Random123 distribution (kat_vectors, philox4x32_10):
// counter = key = 0 -> 6627e8d5 e169c58d bc57ac4c 9b00dbd8.
TEST(Philox, MatchesRandom123KnownAnswer) {
  const auto r = Philox4x32::generate({0, 0, 0, 0}, {0, 0});
  EXPECT_EQ(r[0], 0x6627e8d5U);
  EXPECT_EQ(r[1], 0xe169c58dU);
  EXPECT_EQ(r[2], 0xbc57ac4cU);
  EXPECT_EQ(r[3], 0x9b00dbd8U);
}

// Random123 kat: counter = key = all ones -> 408f276d 41c83b0e a20bc7c6 6d5451fd.
TEST(Philox, MatchesRandom123KnownAnswerOnes) {
  const auto r = Philox4x32::generate({0xffffffffU, 0xffffffffU, 0xffffffffU, 0xffffffffU},
                                      {0xffffffffU, 0xffffffffU});
  EXPECT_EQ(r[0], 0x408f276dU);
  EXPECT_EQ(r[1], 0x41c83b0eU);
  EXPECT_EQ(r[2], 0xa20bc7c6U);
  EXPECT_EQ(r[3], 0x6d5451fdU);
}

TEST(CounterRng, PureFunctionOfKey) {
  CounterRng a{42}, b{42}, c{43};
  EXPECT_EQ(a.uniform2(Purpose::kTest, 7, 1, 2), b.uniform2(Purpose::kTest, 7, 1, 2));
  EXPECT_NE(a.uniform2(Purpose::kTest, 7, 1, 2), c.uniform2(Purpose::kTest, 7, 1, 2));
  EXPECT_NE(a.uniform2(Purpose::kTest, 7, 1, 2), a.uniform2(Purpose::kTest, 8, 1, 2));
  EXPECT_NE(a.uniform2(Purpose::kTest, 7, 1, 2), a.uniform2(Purpose::kPairNoise, 7, 1, 2));
  EXPECT_NE(a.uniform2(Purpose::kTest, 7, 1, 2), a.uniform2(Purpose::kTest, 7, 1, 2, 1));
  // Steps that differ only above bit 32 must differ too.
  EXPECT_NE(a.uniform2(Purpose::kTest, 1, 1, 2),
            a.uniform2(Purpose::kTest, 1 + (1ULL << 32), 1, 2));
}

// Stochastic: 2e5 normals; mean within 5 SE and variance within 5 SE of 1
// (false-failure rate < 1e-6 per assertion).
TEST(CounterRng, NormalsHaveUnitVariance) {
  CounterRng rng{2024};
  const int n = 100000;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    const auto z = rng.normal2(Purpose::kTest, 0, static_cast<std::uint32_t>(i), 0);
    sum += z[0] + z[1];
    sum2 += z[0] * z[0] + z[1] * z[1];
  }
  const double m = sum / (2 * n), v = sum2 / (2 * n) - m * m;
  EXPECT_LT(std::abs(m), 5.0 / std::sqrt(2.0 * n));
  EXPECT_LT(std::abs(v - 1.0), 5.0 * std::sqrt(2.0 / (2.0 * n)));
}

TEST(Xoshiro, StreamsAreReproducibleAndIndependent) {
  Xoshiro256 a(1, 0), b(1, 0), c(1, 1), d(2, 0);
  const std::uint64_t fa = a.next();
  EXPECT_EQ(fa, b.next());
  EXPECT_NE(fa, c.next());
  EXPECT_NE(fa, d.next());
}

TEST(Xoshiro, StateRoundTripContinuesIdentically) {
  Xoshiro256 g(99, 3);
  for (int i = 0; i < 1000; ++i) g.next();
  Xoshiro256 copy;
  copy.set_state(g.state());
  for (int i = 0; i < 1000; ++i) ASSERT_EQ(g.next(), copy.next());
}

// Stochastic: mean of 1e6 Exp(1) within 5 SE (SE = 1e-3); false-failure < 1e-6.
TEST(Xoshiro, ExponentialHasUnitMeanAndIsPositive) {
  Xoshiro256 g(5);
  double sum = 0;
  for (int i = 0; i < 1000000; ++i) {
    const double e = g.exponential();
    ASSERT_GT(e, 0.0);
    ASSERT_TRUE(std::isfinite(e));
    sum += e;
  }
  EXPECT_NEAR(sum / 1e6, 1.0, 5e-3);
}

TEST(Seeds, MixSeedSeparatesRealizations) {
  std::set<std::uint64_t> seen;
  for (std::uint64_t r = 0; r < 1000; ++r) seen.insert(mix_seed(12345, r));
  EXPECT_EQ(seen.size(), 1000u);
  EXPECT_EQ(mix_seed(1, 2), mix_seed(1, 2));
}

}  // namespace
}  // namespace sadr::rng
