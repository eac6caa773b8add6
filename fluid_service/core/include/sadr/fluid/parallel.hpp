// SPDX-License-Identifier: MIT
/// \file parallel.hpp
/// Threading policy of the fluid loops: OpenMP `parallel for` over particles, only above
/// kMinParallel particles for the pair loops and kMinParallelLight for the per-particle loops
/// of a few operations each (integrator updates, limits, health checks, per-particle
/// prefactors). With passive waits (sadr's default) every parallel region wakes the team's
/// sleeping threads, ~50-100 us on a VM whose idle vCPUs halt: the general SDPD sub-step has
/// ~10 regions, and with all of them threaded from 1024 particles two threads were slower than
/// one at 1300-1900 particles (yeast_cell_channel, 1553 particles: 1.3-1.5x). The light loops
/// cost 10-40 ns per particle, so they only pay from ~1e4 particles; measured with them serial
/// below 16384: 1.5-1.9x faster at 1250-1900 particles and 7 % at 10700 (general path), the
/// fused bulk path unchanged (bench/results/README-fluid.md, round 6). Results never depend on
/// either threshold: every loop is a per-particle gather with a fixed summation order, and
/// the reductions are max/min.
#pragma once

#include <cstdint>
#ifdef SADR_HAVE_OPENMP
#include <omp.h>
#endif

namespace sadr::fluid {

inline constexpr std::int64_t kMinParallel = 1024;
/// Per-particle loops of a few operations (see above).
inline constexpr std::int64_t kMinParallelLight = 16384;

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
