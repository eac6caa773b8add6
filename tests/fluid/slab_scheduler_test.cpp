// SPDX-License-Identifier: MIT
// Property: the core SlabScheduler (slab_scheduler.hpp). partition_and_filter keeps every pair
// of a full list exactly once, each within kReach slabs ahead (mod the count on a periodic axis);
// run() visits every slab once per pass, and an order-sensitive scatter over the forward pairs
// gives the same bits on 1 and 2 threads (each particle receives its contributions in the order
// (phase, slab, member)).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <set>
#include <utility>
#include <vector>

#include "sadr/common/rng.hpp"
#include "sadr/fluid/neighbor_list.hpp"
#include "sadr/fluid/slab_scheduler.hpp"
#ifdef SADR_HAVE_OPENMP
#include <omp.h>
#endif

namespace sadr::fluid {
namespace {

struct Cloud {
  Box box;
  std::vector<double> x;
  double cutoff;
};

Cloud cloud(int dim, bool periodic_last, int n, double cutoff) {
  Cloud c;
  c.cutoff = cutoff;
  c.box.dimension = dim;
  for (int a = 0; a < 3; ++a) {
    c.box.lo[a] = 0;
    c.box.hi[a] = a < dim ? 8.0 : 1.0;
    c.box.periodic[a] = a < dim && (a < dim - 1 || periodic_last);
  }
  rng::Xoshiro256 gen(11, static_cast<std::uint64_t>(n + dim));
  c.x.assign(3 * static_cast<std::size_t>(n), 0.0);
  for (int i = 0; i < n; ++i) {
    for (int a = 0; a < dim; ++a) c.x[3 * i + a] = gen.uniform() * 8.0;
  }
  return c;
}

TEST(SlabScheduler, ForwardFilterKeepsEveryPairOnceWithinReach) {
  for (const bool periodic : {true, false}) {
    for (const int dim : {1, 2, 3}) {
      const Cloud c = cloud(dim, periodic, dim == 1 ? 200 : 600, 1.1);
      NeighborList full, fwd;
      CellListBuilder(c.box, c.cutoff).build(c.x, full);
      fwd = full;
      SlabScheduler s;
      s.partition_and_filter(PeriodicBox(c.box), dim - 1, c.cutoff, c.x, fwd);
      const SlabPartition& p = s.partition();
      ASSERT_GT(p.count, SlabScheduler::kColours) << "dim " << dim;
      if (periodic) {
        EXPECT_EQ(p.count % SlabScheduler::kColours, 0U);
      }
      const std::size_t n = c.x.size() / 3;
      std::vector<std::uint32_t> slab(n, 0);
      for (std::uint32_t q = 0; q < p.count; ++q) {
        for (std::uint32_t k = p.start[q]; k < p.start[q + 1]; ++k) slab[p.members[k]] = q;
      }
      std::set<std::pair<std::uint32_t, std::uint32_t>> want, got;
      for (std::uint32_t i = 0; i < n; ++i) {
        for (const std::uint32_t j : full.of(i)) want.insert({std::min(i, j), std::max(i, j)});
        for (const std::uint32_t j : fwd.of(i)) {
          EXPECT_TRUE(got.insert({std::min(i, j), std::max(i, j)}).second) << i << "," << j;
          std::uint32_t ds = slab[j] - slab[i];
          if (periodic && slab[j] < slab[i]) ds += p.count;
          EXPECT_LE(ds, SlabScheduler::kReach) << i << "," << j;
          if (ds == 0) {
            EXPECT_GT(j, i);
          }
        }
      }
      EXPECT_EQ(got, want) << "dim " << dim << " periodic " << periodic;
    }
  }
}

/// An order-sensitive scatter (h <- h * 3 + pair term, both sides) on the forward pairs.
std::vector<double> scatter(const Cloud& c, const NeighborList& fwd, SlabScheduler& s, int passes) {
  const std::size_t n = c.x.size() / 3;
  std::vector<double> h(n, 1.0);
  std::vector<int> visits(s.count(), 0);
  for (int pass = 0; pass < passes; ++pass) {
    s.run(
        [&](const std::uint32_t* first, const std::uint32_t* last, std::size_t) {
          if (first != last) {
            for (std::uint32_t q = 0; q < s.count(); ++q) {
              if (s.partition().members.data() + s.partition().start[q] == first) ++visits[q];
            }
          }
          for (; first != last; ++first) {
            const std::uint32_t i = *first;
            for (const std::uint32_t j : fwd.of(i)) {
              const double t = 1e-3 * (c.x[3 * i] - c.x[3 * j]);
              h[i] = h[i] * 1.0000001 + t;
              h[j] = h[j] * 1.0000001 - t;
            }
          }
        },
        true);
  }
  for (std::uint32_t q = 0; q < s.count(); ++q) {
    if (s.partition().start[q + 1] > s.partition().start[q]) {
      EXPECT_EQ(visits[q], passes) << "slab " << q;
    }
  }
  return h;
}

TEST(SlabScheduler, ScatterIsTheSameOnOneAndTwoThreads) {
#ifdef SADR_HAVE_OPENMP
  const Cloud c = cloud(2, true, 4000, 0.5);
  NeighborList fwd;
  CellListBuilder(c.box, c.cutoff).build(c.x, fwd);
  SlabScheduler s;
  s.partition_and_filter(PeriodicBox(c.box), 1, c.cutoff, c.x, fwd);
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  const auto one = scatter(c, fwd, s, 3);
  omp_set_num_threads(2);
  const auto two = scatter(c, fwd, s, 3);
  omp_set_num_threads(saved);
  ASSERT_EQ(one.size(), two.size());
  EXPECT_EQ(std::memcmp(one.data(), two.data(), one.size() * sizeof(double)), 0);
#else
  GTEST_SKIP() << "built without OpenMP";
#endif
}

}  // namespace
}  // namespace sadr::fluid
