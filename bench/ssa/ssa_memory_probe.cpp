// SPDX-License-Identifier: MIT
/// \file ssa_memory_probe.cpp
/// Where the NSM process memory is (issue 20), on ssa_bench's case (a) lattice (6 face
/// neighbours, 3 molecules per voxel): per phase, the resident set (VmRSS: it includes the
/// huge-page arrays, which bypass operator new) and the counted operator-new heap
/// (bench/common/heap_counter), per voxel; then each large array's capacity per voxel.
/// Usage: ssa_memory_probe [side]   (default 64)
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "heap_counter.hpp"
#include "sadr/ssa/nsm_solver.hpp"
#include "ssa_scenes.hpp"

namespace {

double vm_rss_bytes() {
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line)) {
    if (line.rfind("VmRSS:", 0) == 0) return 1024.0 * std::atof(line.c_str() + 6);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace sadr::ssa;
  using namespace sadr::ssa::bench;
  const int n = argc > 1 ? std::atoi(argv[1]) : 64;
  const double nv = static_cast<double>(n) * n * n;
  const long long base = sadr::bench::heap_live();
  double rss = vm_rss_bytes();
  auto phase = [&](const char* name, auto&& fn) {
    sadr::bench::heap_phase(name, nv, base, fn);
    const double now = vm_rss_bytes();
    std::printf("  %-40s VmRSS +%7.1f\n", "", (now - rss) / nv);
    rss = now;
  };
  std::printf("%d^3 = %.0f voxels, bytes per voxel (heap: operator new only)\n", n, nv);
  const Model m = lattice_model(3, n, 1.2, false);
  sadr::ParticleState p;
  phase("lattice (the caller's ParticleState)", [&] { p = lattice(3, n, 1.0, 0.0, 1); });
  NsmSolver s(m, 12345);
  phase("update_graph", [&] { s.update_graph(p); });
  phase("set_counts (3 per voxel)",
        [&] { s.set_counts(0, scatter(p.size(), static_cast<std::int64_t>(3 * nv), 1)); });
  phase("advance (1e5 events)", [&] { s.advance(s.time() + 1e5 / (3 * nv * 6)); });
  const DiffusionGraph& g = s.graph();
  auto cap = [nv](const auto& v) { return static_cast<double>(v.capacity() * sizeof(v[0])) / nv; };
  std::printf(
      "graph: edges %.1f (%.2f per voxel x %zu B), row_start %.1f, split %.1f, sum_all "
      "%.1f, sum_nowall %.1f, volume %.1f, is_wall %.1f, kind %.1f, wall_distance %.1f\n",
      cap(g.edges), static_cast<double>(g.edges.size()) / nv, sizeof(g.edges[0]), cap(g.row_start),
      cap(g.split), cap(g.sum_all), cap(g.sum_nowall), cap(g.volume), cap(g.is_wall), cap(g.kind),
      cap(g.wall_distance));
  std::printf("graph builder: %.2f candidates per voxel (4 B each; its other arrays are private)\n",
              static_cast<double>(s.state().graph_builder().candidate_count()) / nv);
  std::printf(
      "the caller's ParticleState: positions %.1f, velocities %.1f, masses %.1f, "
      "densities %.1f\n",
      cap(p.positions), cap(p.velocities), cap(p.masses), cap(p.densities));
  return 0;
}
