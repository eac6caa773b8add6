// SPDX-License-Identifier: MIT
/// \file fluid_memory_probe.cpp
/// Where the SDPD process peak memory is (issue 20): a counting global operator new/delete
/// (bench/common/heap_counter) tracks the live heap bytes and their peak per phase (lattice,
/// initialize, first advance, further advances), and one neighbour-list build on its own (its
/// transient peak and what it keeps). Bench-only: the counting allocator would perturb
/// fluid_bench's timings. Usage: fluid_memory_probe D N [steps]   (one thread; prints bytes per
/// particle)
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "fluid_bench_case.hpp"
#include "heap_counter.hpp"
#include "sadr/fluid/neighbor_list.hpp"
#include "sdpd/sdpd_backend.hpp"
#ifdef SADR_HAVE_OPENMP
#include <omp.h>
#endif

using sadr::bench::heap_live;
using sadr::bench::heap_phase;

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s D N [steps]\n", argv[0]);
    return 2;
  }
#ifdef SADR_HAVE_OPENMP
  omp_set_num_threads(1);
#endif
  const int dim = std::atoi(argv[1]);
  const long n_target = std::atol(argv[2]);
  const int steps = argc > 3 ? std::atoi(argv[3]) : 2;
  sadr::fluid::FluidModel m;
  const long long base = heap_live();
  sadr::ParticleState p = sadr::fluid::bench::bench_case(dim, n_target, m);
  const double np = static_cast<double>(p.size());
  auto per = [np](long long b) { return static_cast<double>(b) / np; };
  std::printf(
      "%dD %.0f particles, one thread, heap bytes per particle (live = held after, "
      "peak = highest live during)\n",
      dim, np);
  std::printf("  lattice (the caller's ParticleState)   live %7.1f\n", per(heap_live() - base));
  auto phase = [&](const char* name, auto&& fn) { heap_phase(name, np, base, fn); };
  sadr::fluid::SdpdBackend b;
  phase("initialize", [&] { b.initialize(m, p, {}); });
  phase("advance 0 (first list build)", [&] { b.advance(0, 0.02); });
  for (int s = 1; s <= steps; ++s) phase("advance", [&] { b.advance(s, 0.02); });
  std::printf("  SdpdBackend::memory_bytes()            %7.1f  (list builds %llu)\n",
              per(static_cast<long long>(b.memory_bytes())),
              static_cast<unsigned long long>(b.list_builds()));
  // One list build on its own, with the backend's cutoff (h (1 + skin)).
  sadr::fluid::NeighborList list;
  const sadr::fluid::CellListBuilder builder(m.box, m.smoothing_length * (1.0 + m.neighbor_skin));
  phase("CellListBuilder::build (full list)", [&] { builder.build(p.positions, list); });
  std::printf("  full list: %.1f entries per particle = %.1f B (capacity %.1f B), offsets %.1f B\n",
              per(static_cast<long long>(list.indices.size())),
              per(static_cast<long long>(4 * list.indices.size())),
              per(static_cast<long long>(4 * list.indices.capacity())),
              per(static_cast<long long>(4 * list.offsets.capacity())));
  phase("CellListBuilder::build again (rebuild)", [&] { builder.build(p.positions, list); });
  return 0;
}
