// SPDX-License-Identifier: MIT
/// \file event_heap.hpp
/// Indexed 4-ary min-heap of next-event times, one entry per voxel, with O(1)
/// lookup of a voxel's slot (the NSM event queue, Elf & Ehrenberg 2004).
///
/// Why 4-ary: half the depth of a binary heap, and the four children of a node
/// are contiguous. Entries are 16 bytes (time, voxel) and the array is offset
/// by 3 slots in a 64-byte aligned buffer so that every group of siblings
/// {4k+1 .. 4k+4} occupies exactly one cache line. Four +inf sentinel slots
/// after the last entry make the sift-down branch-free (see sift_down()).
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <new>
#include <span>
#include <vector>

namespace sadr::ssa {

class EventHeap4 {
 public:
  struct Entry {
    double time;          ///< next event time [T] (+inf = never)
    std::uint32_t voxel;  ///< voxel index
  };

  EventHeap4() = default;
  EventHeap4(const EventHeap4& other) { *this = other; }
  EventHeap4& operator=(const EventHeap4& other);
  EventHeap4(EventHeap4&&) noexcept = default;
  EventHeap4& operator=(EventHeap4&&) noexcept = default;

  /// Builds the heap with voxel i at times[i], O(N) (Floyd heapify).
  void assign(std::span<const double> times);
  /// Rebuilds from a stored entry array (a snapshot); validates the heap property.
  void assign_entries(std::span<const Entry> entries);

  [[nodiscard]] std::size_t size() const { return n_; }
  [[nodiscard]] bool empty() const { return n_ == 0; }
  /// Earliest entry (requires !empty()).
  [[nodiscard]] const Entry& top() const { return at(0); }
  /// Current event time of `voxel`.
  [[nodiscard]] double time_of(std::uint32_t voxel) const { return at(pos_[voxel]).time; }
  /// Sets the time of `voxel` and restores the heap property, O(log_4 N).
  void update(std::uint32_t voxel, double time) {
    const std::uint32_t p = pos_[voxel];
    const double old = at(p).time;
    if (time < old) {
      sift_up(p, Entry{time, voxel});
    } else {
      sift_down(p, Entry{time, voxel});
    }
  }
  /// Fast path for the root (the voxel that just fired).
  void update_top(double time) { sift_down(0, Entry{time, at(0).voxel}); }

  /// Entries in heap order (for snapshots).
  [[nodiscard]] std::vector<Entry> entries() const;
  /// True if the heap property and the slot index hold (tests).
  [[nodiscard]] bool valid() const;

 private:
  static constexpr std::size_t kOffset = 3;  // slot k lives at data_[k + 3]
  Entry& at(std::size_t k) { return data_[k + kOffset]; }
  [[nodiscard]] const Entry& at(std::size_t k) const { return data_[k + kOffset]; }
  void allocate(std::size_t n);

  void sift_up(std::size_t k, Entry e) {
    while (k > 0) {
      const std::size_t parent = (k - 1) >> 2;
      if (!(e.time < at(parent).time)) break;
      at(k) = at(parent);
      pos_[at(k).voxel] = static_cast<std::uint32_t>(k);
      k = parent;
    }
    at(k) = e;
    pos_[e.voxel] = static_cast<std::uint32_t>(k);
  }

  void sift_down(std::size_t k, Entry e) {
    // Slots n_ .. n_ + 3 hold +inf sentinels, so every node with a child has four
    // children slots and the minimum of four is taken without bounds checks and
    // without branches (setcc / minsd). With the no-wall fire path, advance() went
    // from 3.3 to 2.5 conditional mispredicts and 834 to 701 instructions per event
    // (callgrind --branch-sim, scenario a). A sentinel is never moved (+inf < t is false).
    for (;;) {
      const std::size_t first = 4 * k + 1;
      if (first >= n_) break;
      const Entry* c = &at(first);
      // The 16 grandchildren of k are 4 consecutive cache lines: start loading
      // them now, so the next level's miss overlaps this level's (+76 instructions
      // per event; median wall time better in 3 interleaved comparisons, minima in 2
      // of 3, all within the shared machine's noise: bench/results/README-ssa.md).
      if (4 * first + 1 < n_) {
        const char* g = reinterpret_cast<const char*>(&at(4 * first + 1));
        __builtin_prefetch(g);
        __builtin_prefetch(g + 64);
        __builtin_prefetch(g + 128);
        __builtin_prefetch(g + 192);
      }
      const double t0 = c[0].time, t1 = c[1].time, t2 = c[2].time, t3 = c[3].time;
      // Index by mask arithmetic on the comparison results (GCC 12 turns "c ? a : b"
      // on the indices into branches); ties keep the lower slot.
      // The minima are written with the opposite comparison (equal on ties), so that
      // GCC does not merge them with the index selection into one branch.
      const std::size_t i01 = static_cast<std::size_t>(t1 < t0);
      const double m01 = t0 < t1 ? t0 : t1;  // minsd
      const std::size_t i23 = 2 + static_cast<std::size_t>(t3 < t2);
      const double m23 = t2 < t3 ? t2 : t3;
      const std::size_t take23 = std::size_t{0} - static_cast<std::size_t>(m23 < m01);
      const std::size_t best = first + (i01 ^ ((i01 ^ i23) & take23));
      const double best_t = m23 < m01 ? m23 : m01;
      if (!(best_t < e.time)) break;
      at(k) = at(best);
      pos_[at(k).voxel] = static_cast<std::uint32_t>(k);
      k = best;
    }
    at(k) = e;
    pos_[e.voxel] = static_cast<std::uint32_t>(k);
  }

  struct AlignedFree {
    void operator()(Entry* p) const { ::operator delete[](p, std::align_val_t{64}); }
  };
  std::unique_ptr<Entry[], AlignedFree> data_;
  std::vector<std::uint32_t> pos_;
  std::size_t n_ = 0;
};

}  // namespace sadr::ssa
