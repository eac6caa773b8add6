// SPDX-License-Identifier: MIT
/// \file parallel.hpp
/// Threading policy of the fluid loops: OpenMP `parallel for` over particles, only above
/// kMinParallel particles (below it a parallel region costs more than it saves, and on an
/// oversubscribed machine spinning threads cost milliseconds per region). Results never
/// depend on it: every loop is a per-particle gather with a fixed summation order.
#pragma once

#include <cstdint>
#ifdef SADR_HAVE_OPENMP
#include <omp.h>
#endif

namespace sadr::fluid {

inline constexpr std::int64_t kMinParallel = 1024;

/// Threads a parallel region may use (1 without OpenMP).
inline int max_threads() {
#ifdef SADR_HAVE_OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}
/// Threads in the calling thread's team (1 outside a parallel region / without OpenMP):
/// may be fewer than requested, so work splits follow this, not max_threads().
inline int team_size() {
#ifdef SADR_HAVE_OPENMP
  return omp_get_num_threads();
#else
  return 1;
#endif
}
/// Index of the calling thread in its parallel region (0 outside one / without OpenMP).
inline int thread_index() {
#ifdef SADR_HAVE_OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

}  // namespace sadr::fluid
