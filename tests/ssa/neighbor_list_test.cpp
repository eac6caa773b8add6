// SPDX-License-Identifier: MIT
// Cell-list neighbour search equals the O(N^2) brute force (Cabana style).
#include "sadr/ssa/neighbor_list.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <tuple>

#include "ssa_test_support.hpp"

namespace sadr::ssa {
namespace {

std::vector<std::vector<std::pair<std::uint32_t, double>>> rows(const NeighborList& nl) {
  std::vector<std::vector<std::pair<std::uint32_t, double>>> out(nl.size());
  for (std::size_t i = 0; i < nl.size(); ++i) {
    for (auto k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k) {
      out[i].emplace_back(nl.col[k], nl.r2[k]);
    }
    std::sort(out[i].begin(), out[i].end());
  }
  return out;
}

class NeighborListVsBruteForce : public ::testing::TestWithParam<std::tuple<int, bool, double>> {};

TEST_P(NeighborListVsBruteForce, SamePairsAndDistances) {
  const auto [dim, periodic, cutoff] = GetParam();
  Box box = testing::make_box(dim, 10.0, periodic);
  box.hi[1] = dim > 1 ? 7.0 : 1.0;  // unequal axes
  std::mt19937_64 gen(42 + dim);
  const std::size_t n = dim == 1 ? 60 : dim == 2 ? 300 : 500;
  std::vector<double> pos(3 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    for (int a = 0; a < dim; ++a) {
      std::uniform_real_distribution<double> u(box.lo[a], box.hi[a]);
      pos[3 * i + a] = u(gen);
    }
  }
  // Walled boxes: particles exactly on the faces are allowed.
  if (!periodic) pos[0] = box.lo[0], pos[3] = box.hi[0];
  const auto fast = rows(build_neighbor_list(box, pos, cutoff));
  const auto slow = rows(brute_force_neighbor_list(box, pos, cutoff));
  ASSERT_EQ(fast.size(), slow.size());
  std::size_t pairs = 0;
  for (std::size_t i = 0; i < n; ++i) {
    ASSERT_EQ(fast[i].size(), slow[i].size()) << "particle " << i;
    for (std::size_t k = 0; k < fast[i].size(); ++k) {
      EXPECT_EQ(fast[i][k].first, slow[i][k].first);
      EXPECT_DOUBLE_EQ(fast[i][k].second, slow[i][k].second);
    }
    pairs += fast[i].size();
  }
  EXPECT_GT(pairs, n);  // the test is not vacuous
}

// Cutoffs: many cells, and 3.4 on a 7-long periodic axis (2 cells: duplicate-cell case).
INSTANTIATE_TEST_SUITE_P(AllCases, NeighborListVsBruteForce,
                         ::testing::Combine(::testing::Values(1, 2, 3), ::testing::Bool(),
                                            ::testing::Values(0.9, 1.7, 3.4)));

TEST(NeighborList, PeriodicImageAcrossTheBoundary) {
  const Box box = testing::make_box(1, 10.0, true);
  const std::vector<double> pos = {0.1, 0, 0, 9.9, 0, 0, 5.0, 0, 0};
  const NeighborList nl = build_neighbor_list(box, pos, 0.5);
  ASSERT_EQ(nl.row_start[1] - nl.row_start[0], 1u);
  EXPECT_EQ(nl.col[nl.row_start[0]], 1u);
  EXPECT_NEAR(nl.r2[nl.row_start[0]], 0.04, 1e-12);
  EXPECT_EQ(nl.row_start[3] - nl.row_start[2], 0u);
}

}  // namespace
}  // namespace sadr::ssa
