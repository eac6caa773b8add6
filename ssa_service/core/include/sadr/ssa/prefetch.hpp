// SPDX-License-Identifier: MIT
/// \file prefetch.hpp
/// Software prefetch for the NSM event loop.
#pragma once

namespace sadr::ssa {

namespace detail {
/// Prefetches the cache line holding p into all levels. An asm statement, not
/// __builtin_prefetch: GCC 12 (-O2 and -O3) deleted whole functions made of
/// __builtin_prefetch calls (the loop's prefetch of the next voxel's record, edge
/// row and counts compiled to nothing; bench/results/ssa_event_loop.md). Never
/// dereferences p.
inline void prefetch_line(const void* p) {
#if defined(__x86_64__) || defined(__i386__)
  asm volatile("prefetcht0 %0" : : "m"(*static_cast<const char*>(p)));
#else
  __builtin_prefetch(p);
#endif
}
}  // namespace detail

}  // namespace sadr::ssa
