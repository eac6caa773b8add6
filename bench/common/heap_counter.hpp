// SPDX-License-Identifier: MIT
/// \file heap_counter.hpp
/// Live heap bytes and their peak (issue 20): linking heap_counter.cpp replaces the global
/// operator new/delete with counting ones. Bench-only probes (it would perturb timings).
#pragma once

#include <cstdio>

namespace sadr::bench {

long long heap_live();  ///< bytes allocated by operator new and not yet freed (usable sizes)
long long heap_peak();  ///< highest heap_live() since heap_reset_peak()
void heap_reset_peak();

/// Runs fn and prints the heap per unit (particle, voxel) relative to `base`: held after, the
/// peak during, and the peak above the start.
template <typename Fn>
void heap_phase(const char* name, double units, long long base, Fn&& fn) {
  const long long before = heap_live();
  heap_reset_peak();
  fn();
  const double live = static_cast<double>(heap_live() - base) / units;
  const double peak = static_cast<double>(heap_peak() - base) / units;
  const double rise = static_cast<double>(heap_peak() - before) / units;
  std::printf("  %-40s live %7.1f  peak %7.1f  (peak above its start %7.1f)\n", name, live, peak,
              rise);
}

}  // namespace sadr::bench
