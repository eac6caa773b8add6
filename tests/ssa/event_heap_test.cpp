// SPDX-License-Identifier: MIT
#include "sadr/ssa/event_heap.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

namespace sadr::ssa {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Brute force: earliest time, lowest voxel on ties.
std::uint32_t brute_top(const std::vector<double>& t) {
  return static_cast<std::uint32_t>(std::min_element(t.begin(), t.end()) - t.begin());
}

TEST(EventTree, RandomUpdatesMatchBruteForce) {
  std::mt19937_64 gen(7);
  std::uniform_real_distribution<double> u(0.0, 100.0);
  // Sizes around the fan-out powers (8, 64, 512) and with partial last nodes.
  for (std::size_t n : {1u, 2u, 5u, 8u, 9u, 17u, 63u, 64u, 65u, 513u, 1000u, 4100u}) {
    std::vector<double> t(n);
    for (auto& x : t) x = u(gen);
    t[0] = kInf;
    EventTree q;
    q.assign(t);
    ASSERT_TRUE(q.valid());
    for (int step = 0; step < 3000; ++step) {
      const auto v = static_cast<std::uint32_t>(gen() % n);
      // Coarse values (multiples of 0.5) make exact ties frequent.
      double nt = std::floor(u(gen) * 2) / 2;
      if (step % 11 == 0) nt = kInf;
      if (step % 3 == 0) {
        t[q.top_voxel()] = nt;
        // Both versions of update_top (AVX-512 where available, and portable).
        if (step % 2 == 0) {
          q.update_top(nt);
        } else {
          q.update_top_portable(nt);
        }
      } else {
        t[v] = nt;
        q.update(v, nt);
      }
      const std::uint32_t expect = brute_top(t);
      ASSERT_EQ(q.top_time(), t[expect]) << "n = " << n << " step " << step;
      ASSERT_EQ(q.top_voxel(), expect) << "n = " << n << " step " << step;
    }
    ASSERT_TRUE(q.valid());
    for (std::uint32_t v = 0; v < n; ++v) ASSERT_EQ(q.time_of(v), t[v]);
    ASSERT_TRUE(std::equal(t.begin(), t.end(), q.times().begin(), q.times().end()));
  }
}

// Brute force runner-up: earliest time other than the top, lowest voxel on ties;
// the top itself when every other time is +inf.
std::uint32_t brute_runner_up(const std::vector<double>& t) {
  const std::uint32_t top = brute_top(t);
  std::uint32_t best = top;
  for (std::uint32_t v = 0; v < t.size(); ++v) {
    if (v == top || t[v] == kInf) continue;
    if (best == top || t[v] < t[best]) best = v;
  }
  return best;
}

TEST(EventTree, RunnerUpMatchesBruteForceAndKeepsTheTreeExact) {
  // The event loop's pattern: update_top, runner_up, update(j), ... runner_up()
  // keeps the top's sibling minima for the next update_top() unless an update()
  // writes into their lines; every step is checked against brute force.
  std::mt19937_64 gen(11);
  std::uniform_real_distribution<double> u(0.0, 100.0);
  for (std::size_t n : {1u, 2u, 7u, 8u, 9u, 64u, 65u, 513u, 4100u}) {
    std::vector<double> t(n);
    for (auto& x : t) x = u(gen);
    EventTree q;
    q.assign(t);
    for (int step = 0; step < 4000; ++step) {
      const int kind = static_cast<int>(gen() % 4);
      double nt = std::floor(u(gen) * 2) / 2;  // frequent exact ties
      if (step % 13 == 0) nt = kInf;
      if (kind == 0) {
        t[q.top_voxel()] = nt;
        if (step % 2 == 0) {
          q.update_top(nt);
        } else {
          q.update_top_portable(nt);
        }
      } else if (kind == 1) {
        // A neighbour of the top (same or nearby line), or anywhere.
        const auto v = static_cast<std::uint32_t>(step % 2 == 0 ? (q.top_voxel() + gen() % 17) % n
                                                                : gen() % n);
        t[v] = nt;
        q.update(v, nt);
      } else {
        const std::uint32_t r = step % 2 == 0 ? q.runner_up() : q.runner_up_portable();
        ASSERT_EQ(r, brute_runner_up(t)) << "n = " << n << " step " << step;
      }
      const std::uint32_t expect = brute_top(t);
      ASSERT_EQ(q.top_voxel(), expect) << "n = " << n << " step " << step;
      ASSERT_EQ(q.top_time(), t[expect]) << "n = " << n << " step " << step;
      if (step % 97 == 0) {
        ASSERT_TRUE(q.valid()) << "n = " << n << " step " << step;
      }
    }
    ASSERT_TRUE(q.valid());
  }
}

TEST(EventTree, StateIsAFunctionOfTheTimes) {
  // Snapshots store only the times: a tree rebuilt from them must equal the
  // updated one, including which voxel wins a tie.
  std::vector<double> t = {5, 3, 8, 1, 9, 2, 7, 1, 4, 1};
  EventTree a;
  a.assign(t);
  EXPECT_EQ(a.top_voxel(), 3u);  // 1 at voxels 3, 7, 9: the lowest index
  a.update(3, 6);
  EXPECT_EQ(a.top_voxel(), 7u);
  a.update_top(0.5);  // voxel 7
  EXPECT_EQ(a.top_voxel(), 7u);
  a.update(9, 0.5);
  EXPECT_EQ(a.top_voxel(), 7u);
  a.update(7, 2);
  EXPECT_EQ(a.top_voxel(), 9u);
  EventTree b;
  b.assign(a.times());
  EXPECT_TRUE(a.valid());
  EXPECT_EQ(b.top_voxel(), a.top_voxel());
  EventTree c = a;  // copy is independent
  c.update(9, 100);
  EXPECT_EQ(a.top_voxel(), 9u);
  EXPECT_EQ(c.top_voxel(), 5u);
}

TEST(EventTree, AllIdleAndEmpty) {
  EventTree e;
  e.assign({});
  EXPECT_TRUE(e.empty());
  EXPECT_TRUE(e.valid());
  std::vector<double> t(20, kInf);
  EventTree q;
  q.assign(t);
  EXPECT_EQ(q.top_time(), kInf);
  EXPECT_EQ(q.top_voxel(), 0u);
  q.update(13, 2.0);
  EXPECT_EQ(q.top_voxel(), 13u);
  q.update_top(kInf);
  EXPECT_EQ(q.top_time(), kInf);
  EXPECT_EQ(q.top_voxel(), 0u);
  EXPECT_TRUE(q.valid());
}

TEST(HugePages, AllocatorRoundTripsLargeAndSmall) {
  // Both paths of the allocator (small: aligned operator new; large: mmap'd whole
  // huge pages) hold their data and are 64-byte aligned.
  for (std::size_t n : {std::size_t{10}, std::size_t{3} << 18}) {
    std::vector<double, detail::HugePageAllocator<double>> v(n, 1.5);
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(v.data()) % 64, 0u);
    v.back() = 2.5;
    EXPECT_EQ(v.front(), 1.5);
    EXPECT_EQ(v.back(), 2.5);
    v.resize(2 * n, 3.5);  // reallocation copies and frees the old block
    EXPECT_EQ(v[n - 1], 2.5);
    EXPECT_EQ(v[2 * n - 1], 3.5);
  }
}

}  // namespace
}  // namespace sadr::ssa
