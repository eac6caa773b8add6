// SPDX-License-Identifier: MIT
/// \file event_heap.hpp
/// The NSM event queue: next event times of all voxels with the earliest one at
/// the top (Elf & Ehrenberg 2004 use an indexed binary heap; any exact priority
/// queue gives the same method).
///
/// Layout: a tournament tree of fan-out kFan = 8 over the time array. Level 0 is
/// the times themselves, by voxel (no slot index: a voxel's time is times[v]);
/// node k of level L >= 1 holds the minimum of its kFan children on level L-1
/// and the voxel that attains it. A node's children are one aligned 64-byte
/// line of times, so recomputing a node is a branch-free SIMD minimum over one
/// line. Why not the indexed 4-ary heap used before: an NSM event moves the
/// fired voxel from the root to a uniformly random rank, i.e. almost always down
/// to a leaf of a log_4 N deep heap, writing the slot index of every entry it
/// passes (random stores). Here the same update recomputes one line per level
/// of a log_8 N deep tree whose upper levels are tiny (N = 32^3: 4096 + 512 +
/// 64 + 8 + 1 nodes, all in L1/L2), and a rescaled jump target usually stops at
/// its first comparison. Measured in bench/results/ssa_event_loop.md.
///
/// Ties: the top is the earliest time and, among equal times, the lowest voxel
/// index. The structure is a pure function of the times (no history), so a
/// snapshot only needs the times.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "sadr/ssa/huge_pages.hpp"
#include "sadr/ssa/prefetch.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace sadr::ssa {

class EventTree {
 public:
  static constexpr unsigned kShift = 3;
  static constexpr std::size_t kFan = std::size_t{1} << kShift;  ///< children per node
  static_assert(kFan == 8, "a node's children are one cache line (and one AVX-512 register)");

  /// Builds the tree with voxel i at times[i], O(N).
  void assign(std::span<const double> times);

  [[nodiscard]] std::size_t size() const { return n_; }
  [[nodiscard]] bool empty() const { return n_ == 0; }
  /// Earliest time (requires !empty()).
  [[nodiscard]] double top_time() const { return min_[min_off_[depth_]]; }
  /// The voxel with the earliest time, lowest index on ties (requires !empty()).
  [[nodiscard]] std::uint32_t top_voxel() const { return arg_[arg_off_[depth_]]; }
  /// Current event time of `voxel`.
  [[nodiscard]] double time_of(std::uint32_t voxel) const { return min_[voxel]; }
  /// Next event times by voxel (N entries).
  [[nodiscard]] std::span<const double> times() const { return {min_.data(), n_}; }
  /// Hints that `voxel`'s time will be read or written soon.
  void prefetch(std::uint32_t voxel) const { detail::prefetch_line(min_.data() + voxel); }

  /// Sets the time of `voxel` and restores the tree, O(log_8 N).
  void update(std::uint32_t voxel, double time);
  /// update(top_voxel(), time), faster: every ancestor of the top is recomputed
  /// (an AVX-512 version when the CPU has it; same results, see event_heap.cpp).
  void update_top(double time);
  /// update_top() without AVX-512 (tests compare the two paths).
  void update_top_portable(double time);

  /// The runner-up: the voxel with the earliest time other than top_voxel(), lowest
  /// index on ties; top_voxel() itself when every other time is +inf or N = 1
  /// (requires !empty()). It is the next top unless the top's or another voxel's
  /// time changes first: the event loop prefetches it two events ahead.
  /// It is the minimum of the sibling minima along the top's path, which the next
  /// update_top() needs too: they are kept (not a const function) and reused by
  /// update_top() unless an update() in between wrote into one of their lines.
  [[nodiscard]] std::uint32_t runner_up();
  /// runner_up() without AVX-512 (tests).
  [[nodiscard]] std::uint32_t runner_up_portable();

  /// True if every node equals the minimum of its children (tests).
  [[nodiscard]] bool valid() const;

 private:
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  static constexpr std::size_t kMaxDepth = 12;  // 8^11 > 2^32 voxels

  /// Lowest index of the minimum of the kFan values at p (64-byte aligned); *m = that minimum.
  static unsigned argmin_line(const double* p, double* m) {
    return argmin_line_with(p, kFan, 0.0, m);  // lane kFan: no substitution
  }
  /// The same with p[lane] read as `value` (lane < kFan; kFan: none).
  static unsigned argmin_line_with(const double* p, std::size_t lane, double value, double* m) {
#if defined(__SSE2__)
    __m128d v[kFan / 2];
    const __m128d sub = _mm_set1_pd(value);
    const __m128d want = _mm_set1_pd(static_cast<double>(lane));
    for (std::size_t k = 0; k < kFan / 2; ++k) {
      const __m128d idx = _mm_set_pd(static_cast<double>(2 * k + 1), static_cast<double>(2 * k));
      const __m128d hit = _mm_cmpeq_pd(idx, want);
      v[k] = _mm_or_pd(_mm_and_pd(hit, sub), _mm_andnot_pd(hit, _mm_load_pd(p + 2 * k)));
    }
    __m128d lo = _mm_min_pd(_mm_min_pd(v[0], v[1]), _mm_min_pd(v[2], v[3]));
    for (std::size_t k = 4; k < kFan / 2; k += 4) {
      lo = _mm_min_pd(lo, _mm_min_pd(_mm_min_pd(v[k], v[k + 1]), _mm_min_pd(v[k + 2], v[k + 3])));
    }
    lo = _mm_min_pd(lo, _mm_shuffle_pd(lo, lo, 1));  // both lanes: the minimum
    unsigned mask = 0;
    for (std::size_t k = 0; k < kFan / 2; ++k) {
      mask |= static_cast<unsigned>(_mm_movemask_pd(_mm_cmpeq_pd(v[k], lo))) << (2 * k);
    }
    *m = _mm_cvtsd_f64(lo);
    return static_cast<unsigned>(__builtin_ctz(mask));
#else
    double x[kFan];
    for (std::size_t k = 0; k < kFan; ++k) x[k] = k == lane ? value : p[k];
    unsigned best = 0;
    for (unsigned k = 1; k < kFan; ++k) best = x[k] < x[best] ? k : best;
    *m = x[best];
    return best;
#endif
  }

  template <unsigned (*Argmin)(const double*, std::size_t, double, double*)>
  [[gnu::always_inline]] inline void update_top_with(double time);
  void update_top_avx512(double time);
  template <unsigned (*Argmin)(const double*, std::size_t, double, double*)>
  [[gnu::always_inline]] inline std::uint32_t runner_up_with();
  std::uint32_t runner_up_avx512();
  /// Sibling minima along the top's path (levels 1..depth_) into sib_*_.
  template <unsigned (*Argmin)(const double*, std::size_t, double, double*)>
  [[gnu::always_inline]] inline void sibling_minima(std::uint32_t top);
  /// update() without the cache bookkeeping; returns the highest level it wrote.
  std::size_t update_levels(std::uint32_t voxel, double time);

  /// Recomputes node `node` of level L >= 1 from its children.
  void recompute(std::size_t L, std::size_t node) {
    double m;
    const std::size_t k =
        node * kFan + argmin_line(min_.data() + min_off_[L - 1] + node * kFan, &m);
    min_[min_off_[L] + node] = m;
    arg_[arg_off_[L] + node] = L == 1 ? static_cast<std::uint32_t>(k) : arg_[arg_off_[L - 1] + k];
  }

  // Levels 0 (the times, by voxel) .. depth_ (the root, one node), each padded to
  // a multiple of kFan with +inf, stored back to back: level L starts at min_off_[L].
  // arg_ holds the voxel attaining each node's minimum (levels >= 1 only).
  std::vector<double, detail::HugePageAllocator<double>> min_;
  std::vector<std::uint32_t> arg_;
  std::size_t min_off_[kMaxDepth + 1] = {};
  std::size_t arg_off_[kMaxDepth + 1] = {};
  std::size_t depth_ = 0;
  std::size_t n_ = 0;
  // Sibling minima, their lanes and voxels along sib_top_'s path (levels 1..depth_),
  // valid while sib_valid_ (runner_up() -> update_top()).
  double sib_min_[kMaxDepth + 1] = {};
  unsigned sib_lane_[kMaxDepth + 1] = {};
  std::uint32_t sib_arg_[kMaxDepth + 1] = {};
  std::uint32_t sib_top_ = 0;
  bool sib_valid_ = false;
};

inline void EventTree::update(std::uint32_t voxel, double time) {
  const std::size_t written = update_levels(voxel, time);
  // Writes on levels 0..written change the lines of levels 0..written on voxel's
  // path; sib_top_'s path shares those lines iff the two voxels agree above bit
  // kShift * (written + 1) (the lines of the nodes of level written + 1).
  const std::uint64_t differ = std::uint64_t{voxel} ^ std::uint64_t{sib_top_};
  if ((differ >> (kShift * (written + 1))) == 0) sib_valid_ = false;
}

inline std::size_t EventTree::update_levels(std::uint32_t voxel, double time) {
  const double old = min_[voxel];
  min_[voxel] = time;
  // Walk up while the changed child changes its parent. `value`/`arg` are the
  // child's new minimum and its voxel; `rose` whether the child's minimum grew.
  std::size_t child = voxel;
  double value = time;
  std::uint32_t arg = voxel;
  bool rose = time > old;
  for (std::size_t L = 1; L <= depth_; ++L) {
    const std::size_t node = child >> kShift;
    double& pmin_ref = min_[min_off_[L] + node];
    std::uint32_t& parg_ref = arg_[arg_off_[L] + node];
    const double pmin = pmin_ref;
    const std::uint32_t parg = parg_ref;
    // The parent's minimum came from this child iff its voxel lies in the child's range.
    const bool from_child = (static_cast<std::size_t>(parg) >> (kShift * (L - 1))) == child;
    if (from_child) {
      if (rose) {
        recompute(L, node);
      } else {
        pmin_ref = value;  // still the (lowest-index) minimum of the siblings
        parg_ref = arg;
      }
    } else if (value < pmin || (value == pmin && arg < parg)) {
      pmin_ref = value;
      parg_ref = arg;
    } else {
      return L - 1;  // this parent, hence every ancestor, is unchanged
    }
    if (pmin_ref == pmin && parg_ref == parg) return L;
    rose = pmin_ref > pmin;
    value = pmin_ref;
    arg = parg_ref;
    child = node;
  }
  return depth_;
}

}  // namespace sadr::ssa
