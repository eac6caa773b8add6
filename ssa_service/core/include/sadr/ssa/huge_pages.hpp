// SPDX-License-Identifier: MIT
/// \file huge_pages.hpp
/// An allocator that puts large arrays on 2 MiB pages (transparent huge pages),
/// for the arrays the NSM event loop reads at random.
#pragma once

#include <cstddef>
#include <new>
#include <utility>

namespace sadr::ssa {

namespace detail {
// Transparent huge pages (2 MiB) for the arrays the NSM event loop reads at
// random (event times, voxel records, counts, edges). Each event touches ~8
// random cache lines of a working set of 4 MiB (32^3 lattice) to 130 MiB (1e6
// voxels); with 4 KiB pages nearly every such access also misses the TLB, and on
// this VM a page walk is itself a chain of misses: a dependent random load over
// 4 MiB costs ~250 ns with 4 KiB pages and ~16 ns with 2 MiB pages
// (bench/results/ssa_event_loop.md). The system runs THP in "madvise" mode, so
// the memory must ask for it. All of it is a hint: without THP the arrays are
// ordinary memory and nothing else changes.

/// 64-byte aligned allocation; from 256 KiB on: 2 MiB aligned, whole huge pages,
/// advised before first touch (so page faults map huge pages).
void* allocate_huge(std::size_t bytes);
void free_huge(void* p, std::size_t bytes);

/// std::allocator replacement for the event loop's large vectors.
template <typename T>
struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() = default;
  template <typename U>
  explicit HugePageAllocator(const HugePageAllocator<U>& /*other*/) {}
  T* allocate(std::size_t n) { return static_cast<T*>(allocate_huge(n * sizeof(T))); }
  void deallocate(T* p, std::size_t n) { free_huge(p, n * sizeof(T)); }
  /// Default-initialises instead of value-initialising: `resize(n)` of a vector of
  /// trivial records leaves the new tail unwritten instead of zeroing it. The graph
  /// rebuild sizes its edge array to the candidate count (plus slack) and trims it
  /// to the edges kept, every step: zeroing that tail (~0.9 MB at 1e4 particles in
  /// 2D) cost a memset per step, and the zero-filled huge pages were reclaimed and
  /// faulted in again (perf: clear_page_erms under GraphBuilder::filter).
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    if constexpr (sizeof...(Args) == 0) {
      ::new (static_cast<void*>(p)) U;
    } else {
      ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
  }
  template <typename U>
  bool operator==(const HugePageAllocator<U>& /*other*/) const {
    return true;
  }
};
}  // namespace detail

}  // namespace sadr::ssa
