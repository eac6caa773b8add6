// SPDX-License-Identifier: MIT
#include "sadr/ssa/event_heap.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>

namespace sadr::ssa {
namespace {

TEST(EventHeap4, RandomUpdatesKeepMinimumAndSlots) {
  std::mt19937_64 gen(7);
  std::uniform_real_distribution<double> u(0.0, 100.0);
  for (std::size_t n : {1u, 2u, 5u, 17u, 1000u}) {
    std::vector<double> t(n);
    for (auto& x : t) x = u(gen);
    t[0] = std::numeric_limits<double>::infinity();
    EventHeap4 heap;
    heap.assign(t);
    ASSERT_TRUE(heap.valid());
    for (int step = 0; step < 3000; ++step) {
      const auto v = static_cast<std::uint32_t>(gen() % n);
      const double nt = (step % 11 == 0) ? std::numeric_limits<double>::infinity() : u(gen);
      if (step % 3 == 0) {
        const std::uint32_t top = heap.top().voxel;
        t[top] = nt;
        heap.update_top(nt);
      } else {
        t[v] = nt;
        heap.update(v, nt);
      }
      const double expect = *std::min_element(t.begin(), t.end());
      ASSERT_EQ(heap.top().time, expect);
      ASSERT_EQ(t[heap.top().voxel], expect);
    }
    ASSERT_TRUE(heap.valid());
    for (std::uint32_t v = 0; v < n; ++v) ASSERT_EQ(heap.time_of(v), t[v]);
  }
}

TEST(EventHeap4, EntriesRoundTripAndRejectsCorruption) {
  std::vector<double> t = {5, 3, 8, 1, 9, 2, 7};
  EventHeap4 a;
  a.assign(t);
  EventHeap4 b;
  b.assign_entries(a.entries());
  ASSERT_TRUE(b.valid());
  EXPECT_EQ(b.top().voxel, 3u);
  auto bad = a.entries();
  bad[1].voxel = bad[2].voxel;
  EXPECT_THROW(b.assign_entries(bad), std::exception);
  EventHeap4 c = a;  // copy
  c.update(3, 100);
  EXPECT_EQ(a.top().voxel, 3u);
  EXPECT_EQ(c.top().voxel, 5u);
}

}  // namespace
}  // namespace sadr::ssa
