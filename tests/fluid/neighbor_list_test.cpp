// SPDX-License-Identifier: MIT
// Property: cell-list neighbour lists equal the O(N^2) brute-force lists (Cabana style).
#include <gtest/gtest.h>

#include "sadr/common/rng.hpp"
#include "sadr/common/status.hpp"
#include "sadr/fluid/neighbor_list.hpp"
#ifdef SADR_HAVE_OPENMP
#include <omp.h>
#endif

namespace sadr::fluid {
namespace {

struct Case {
  int dim;
  std::array<bool, 3> periodic;
  std::array<double, 3> len;
  double cutoff;
  int n;
};

class NeighborParam : public ::testing::TestWithParam<Case> {};

TEST_P(NeighborParam, EqualsBruteForce) {
  const Case c = GetParam();
  Box box;
  box.dimension = c.dim;
  box.periodic = c.periodic;
  for (int a = 0; a < 3; ++a) {
    box.lo[a] = -0.3 * a;
    box.hi[a] = box.lo[a] + c.len[a];
  }
  rng::Xoshiro256 gen(7, static_cast<std::uint64_t>(c.n * 10 + c.dim));
  std::vector<double> x(3 * c.n, 0.0);
  for (int i = 0; i < c.n; ++i) {
    for (int a = 0; a < c.dim; ++a) x[3 * i + a] = box.lo[a] + gen.uniform() * c.len[a];
  }
  NeighborList cell;
  CellListBuilder(box, c.cutoff).build(x, cell);
  const NeighborList brute = brute_force_neighbors(box, c.cutoff, x);
  ASSERT_EQ(cell.offsets, brute.offsets);
  ASSERT_EQ(cell.indices, brute.indices);
  // symmetry: j in list(i) <=> i in list(j)
  std::size_t pairs = 0;
  for (std::size_t i = 0; i < cell.size(); ++i) {
    for (auto j : cell.of(i)) {
      const auto lj = cell.of(j);
      EXPECT_TRUE(std::binary_search(lj.begin(), lj.end(), static_cast<std::uint32_t>(i)));
      ++pairs;
    }
  }
  EXPECT_GT(pairs, 0u);
}

INSTANTIATE_TEST_SUITE_P(
    Boxes, NeighborParam,
    ::testing::Values(
        Case{1, {true, false, false}, {10, 1, 1}, 0.7, 200},
        Case{1, {false, false, false}, {10, 1, 1}, 0.7, 200},
        Case{2, {true, true, false}, {5, 4, 1}, 0.6, 600},
        Case{2, {true, false, false}, {5, 4, 1}, 0.6, 600},
        Case{2, {true, true, false}, {1.3, 4, 1}, 0.6, 300},  // 2 cells on a periodic axis
        Case{3, {true, true, true}, {3, 3, 3}, 0.5, 1500},
        Case{3, {false, true, false}, {3, 2, 2.5}, 0.5, 1200},
        Case{3, {true, true, true}, {1.0, 1.2, 3}, 0.5, 800}));

// The build scans each thread's range into its own buffer: the lists must not depend on the
// thread count (3000 particles: above kMinParallel, so the region really runs threaded).
TEST(NeighborList, SameListsOnAnyThreadCount) {
  Box box;
  box.dimension = 3;
  box.periodic = {true, true, false};
  box.hi = {6.0, 5.0, 4.0};
  rng::Xoshiro256 gen(3, 9);
  std::vector<double> x(3 * 3000);
  for (std::size_t i = 0; i < 3000; ++i) {
    for (int a = 0; a < 3; ++a) x[3 * i + a] = gen.uniform() * box.hi[a];
  }
  const NeighborList brute = brute_force_neighbors(box, 0.7, x);
#ifdef SADR_HAVE_OPENMP
  const int max_threads = omp_get_max_threads();
  for (int threads : {1, 2, 3}) {
    omp_set_num_threads(threads);
#else
  for (int threads : {1}) {
#endif
    NeighborList cell;
    CellListBuilder(box, 0.7).build(x, cell);
    EXPECT_EQ(cell.offsets, brute.offsets) << threads << " threads";
    EXPECT_EQ(cell.indices, brute.indices) << threads << " threads";
  }
#ifdef SADR_HAVE_OPENMP
  omp_set_num_threads(max_threads);
#endif
}

TEST(NeighborList, RejectsTooSmallPeriodicBox) {
  Box box;
  box.dimension = 2;
  box.periodic = {true, true, false};
  box.hi = {1.0, 1.0, 1.0};
  EXPECT_THROW(CellListBuilder(box, 0.6), InvalidArgument);
  EXPECT_THROW(CellListBuilder(box, -1.0), InvalidArgument);
}

}  // namespace
}  // namespace sadr::fluid
