// SPDX-License-Identifier: MIT
// Ensemble mean / unbiased variance against a direct two-pass computation,
// merge of partial accumulators, CSV output; realization seeds.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>

#include "sadr/common/rng.hpp"
#include "sadr/common/status.hpp"
#include "sadr/orchestrator/ensemble_accumulator.hpp"
#include "sadr/orchestrator/hash.hpp"
#include "sadr/orchestrator/seeds.hpp"

namespace sadr::orchestrator {
namespace {

constexpr std::size_t kN = 4;
constexpr std::size_t kRealizations = 9;

/// Deterministic pseudo-random data: value of species s at particle i in realization r.
double value(std::size_t r, std::size_t s, std::size_t i) {
  rng::Xoshiro256 g(1000 + r, 10 * s + i);
  return std::floor(100.0 * g.uniform()) + 1e6 * static_cast<double>(s);  // large offset: stability
}

std::vector<SpeciesColumn> columns(std::size_t r) {
  std::vector<SpeciesColumn> c{{"A", {}}, {"B", {}}};
  for (std::size_t s = 0; s < 2; ++s) {
    for (std::size_t i = 0; i < kN; ++i) c[s].values.push_back(value(r, s, i));
  }
  return c;
}

void expect_matches_direct(const EnsembleAccumulator& acc, std::size_t frame) {
  ASSERT_EQ(acc.realizations(frame), kRealizations);
  for (std::size_t s = 0; s < 2; ++s) {
    for (std::size_t i = 0; i < kN; ++i) {
      double mean = 0;
      for (std::size_t r = 0; r < kRealizations; ++r) mean += value(r, s, i);
      mean /= kRealizations;
      double ss = 0;
      for (std::size_t r = 0; r < kRealizations; ++r) {
        ss += (value(r, s, i) - mean) * (value(r, s, i) - mean);
      }
      const double var = ss / (kRealizations - 1);
      EXPECT_NEAR(acc.mean(frame, s, i), mean, 1e-12 * std::max(1.0, std::abs(mean)));
      EXPECT_NEAR(acc.variance(frame, s, i), var, 1e-9 * std::max(1.0, var));
    }
  }
}

TEST(Ensemble, MeanAndUnbiasedVarianceMatchDirectComputation) {
  EnsembleAccumulator acc({"A", "B"}, kN);
  for (std::size_t r = 0; r < kRealizations; ++r) {
    acc.add(0, 0.0, columns(r));
    acc.add(1, 0.5, columns(r));
  }
  EXPECT_EQ(acc.frame_count(), 2U);
  EXPECT_EQ(acc.time(1), 0.5);
  expect_matches_direct(acc, 0);
  expect_matches_direct(acc, 1);
}

TEST(Ensemble, MergeOfPartialAccumulatorsEqualsOneAccumulator) {
  EnsembleAccumulator a({"A", "B"}, kN);
  EnsembleAccumulator b({"A", "B"}, kN);
  for (std::size_t r = 0; r < kRealizations; ++r) (r % 3 == 0 ? a : b).add(0, 1.0, columns(r));
  a.merge(b);
  expect_matches_direct(a, 0);
}

TEST(Ensemble, SingleRealizationHasNoVariance) {
  EnsembleAccumulator acc({"A", "B"}, kN);
  acc.add(0, 0.0, columns(0));
  EXPECT_TRUE(std::isnan(acc.variance(0, 0, 0)));
  EXPECT_EQ(acc.mean(0, 1, 2), value(0, 1, 2));
}

TEST(Ensemble, RefusesMismatchedInput) {
  EnsembleAccumulator acc({"A", "B"}, kN);
  acc.add(0, 0.0, columns(0));
  EXPECT_THROW(acc.add(0, 0.1, columns(1)), InvalidArgument);  // other time, same frame
  std::vector<SpeciesColumn> missing{{"A", std::vector<double>(kN, 0.0)}};
  EXPECT_THROW(acc.add(1, 0.1, missing), InvalidArgument);
  std::vector<SpeciesColumn> short_col{{"A", {1.0}}, {"B", {1.0}}};
  EXPECT_THROW(acc.add(1, 0.1, short_col), InvalidArgument);
}

TEST(Ensemble, CsvColumns) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("sadr_ens_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  EnsembleAccumulator acc({"A", "B"}, kN);
  for (std::size_t r = 0; r < kRealizations; ++r) acc.add(0, 0.25, columns(r));
  const std::vector<std::uint64_t> ids{10, 11, 12, 13};
  acc.write_csv(0, dir / "mean.csv", ids);
  std::istringstream in(read_file_bytes(dir / "mean.csv"));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "time,id,realizations,A_mean,A_var,B_mean,B_var");
  std::getline(in, line);
  std::vector<double> v;
  std::stringstream cells(line);
  std::string cell;
  while (std::getline(cells, cell, ',')) v.push_back(std::stod(cell));
  ASSERT_EQ(v.size(), 7U);
  EXPECT_EQ(v[0], 0.25);
  EXPECT_EQ(v[1], 10.0);
  EXPECT_EQ(v[2], 9.0);
  EXPECT_EQ(v[3], acc.mean(0, 0, 0));
  EXPECT_EQ(v[4], acc.variance(0, 0, 0));
  std::filesystem::remove_all(dir);
}

TEST(Seeds, RealizationSeedsAreDeterministicAndDistinct) {
  EXPECT_EQ(realization_seed(42, 3), rng::mix_seed(42, 3));
  EXPECT_EQ(realization_seed(42, 3), realization_seed(42, 3));
  std::set<std::uint64_t> seen;
  for (std::uint64_t s : {0ULL, 1ULL, 42ULL}) {
    for (std::uint64_t r = 0; r < 1000; ++r) seen.insert(realization_seed(s, r));
  }
  EXPECT_EQ(seen.size(), 3000U);
  static_assert(realization_seed(1, 2) == rng::mix_seed(1, 2), "usable at compile time");
}

}  // namespace
}  // namespace sadr::orchestrator
