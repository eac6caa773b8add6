// SPDX-License-Identifier: MIT
// ssa core benchmarks (issue 3): prints one JSON object and one summary line.
//
//   ssa_bench a          32^3 periodic lattice, 6 neighbours, 1 species, 1e5 molecules,
//                        pure diffusion, >= 3e7 events
//   ssa_bench b          (a) plus A + B <-> C in every voxel
//   ssa_bench c          100^3 = 1e6 voxels, 6 neighbours, 3e6 molecules, pure diffusion
//   ssa_bench d          2D SPH particle graph (jittered 200^2, h = 3 dx), graph rebuilt
//                        every coupling step at ~1 event per voxel per step; then the
//                        GraphBuilder alone on the same positions
//   ssa_bench boost_csr  our CSR vs boost::compressed_sparse_row_graph on the (a) edges
// Options: --events N (NSM events), --baseline-events N (direct method events; 0: none, so
// that peak_rss_mib is the NSM's alone),
// --n side (lattice side), --move s (scenario d: displacement std dev per axis per step
// in dx, default 0.01; the graph builder searches again once a particle moved > 0.05 h).
// Scenario d times the rebuild by wall clock and CPU (all threads, calling thread): it
// uses OMP_NUM_THREADS threads; run with OMP_WAIT_POLICY=passive (as ssa_service does).
#include <algorithm>
#include <boost/graph/compressed_sparse_row_graph.hpp>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "bench_util.hpp"
#include "sadr/ssa/diffusion_graph.hpp"
#include "sadr/ssa/direct_solver.hpp"
#include "sadr/ssa/graph_builder.hpp"
#include "sadr/ssa/neighbor_list.hpp"
#include "sadr/ssa/nsm_solver.hpp"
#include "ssa_scenes.hpp"

namespace sadr::ssa::bench {
namespace {

struct Options {
  std::string scenario = "a";
  double events = 3.0e7;
  double baseline_events = 3000;
  int n = 0;           // lattice side override (0 = scenario default)
  double move = 0.01;  // scenario d: displacement per axis per step, std dev [dx]
  std::string command;
};

double total_rate(const NsmSolver& s) {
  double a = 0;
  for (std::uint32_t i = 0; i < s.graph().size(); ++i) a += s.voxel_rate(i);
  return a;
}

/// Runs the NSM for ~`events` events; returns CPU seconds, fills the event count.
template <typename Solver>
double run_events(Solver& s, double rate, double events, std::uint64_t& fired) {
  const std::uint64_t e0 = s.events();
  const double t0 = thread_cpu_s();
  s.advance(s.time() + events / rate);
  const double cpu = thread_cpu_s() - t0;
  fired = s.events() - e0;
  return cpu;
}

void emit(Json& j, const std::string& summary) {
  j.num("peak_rss_mib", peak_rss_mib());
  std::printf("%s\n%s\n", j.dump().c_str(), summary.c_str());
}

int lattice_scenario(const Options& o) {
  const bool big = o.scenario == "c";
  const bool rx = o.scenario == "b";
  const int n = o.n > 0 ? o.n : big ? 100 : 32;
  const std::int64_t molecules = o.n > 0 ? static_cast<std::int64_t>(3.0 * n * n * n)
                                 : big   ? 3000000
                                         : 100000;
  const Model m = lattice_model(3, n, 1.2, rx);  // h = 1.2 dx: the 6 face neighbours only
  const ParticleState p = lattice(3, n, 1.0, 0.0, 1);
  NsmSolver s(m, 12345);
  double t0 = thread_cpu_s();
  s.update_graph(p);
  const double build_s = thread_cpu_s() - t0;
  const std::size_t nv = p.size();
  s.set_counts(0, scatter(nv, molecules, 1));
  if (rx) s.set_counts(1, scatter(nv, molecules, 2));
  // Restart cost: all rates + fresh exponential per voxel + O(N) heapify (set_counts
  // with the current counts triggers exactly that, plus an O(N) copy).
  const std::vector<std::int64_t> same(s.counts(0).begin(), s.counts(0).end());
  t0 = thread_cpu_s();
  const int reps = big ? 3 : 20;
  for (int r = 0; r < reps; ++r) s.set_counts(0, same);
  const double restart_s = (thread_cpu_s() - t0) / reps;
  // Warm-up (caches, heap shape) then the measured run.
  std::uint64_t fired = 0;
  run_events(s, total_rate(s), 1e6, fired);
  const double cpu = run_events(s, total_rate(s), o.events, fired);
  const double ns_event = 1e9 * cpu / static_cast<double>(fired);
  // Baseline: the direct method on the same system, fewer events (it is O(N) per event).
  // --baseline-events 0 builds no direct solver, so that the peak RSS is the NSM's alone.
  std::uint64_t dfired = 0;
  double d_ns = 0;
  if (o.baseline_events > 0) {
    DirectSolver d(m, 12345);
    d.update_graph(p);
    d.set_counts(0, scatter(nv, molecules, 1));
    if (rx) d.set_counts(1, scatter(nv, molecules, 2));
    const double dcpu = run_events(d, total_rate(s), o.baseline_events, dfired);
    d_ns = 1e9 * dcpu / static_cast<double>(std::max<std::uint64_t>(dfired, 1));
  }
  const double urdme = o.scenario == "a" ? 245 : o.scenario == "b" ? 369 : 821;
  const double target = o.scenario == "a" ? 120 : o.scenario == "b" ? 150 : 500;
  Json j;
  j.str("scenario", o.scenario);
  j.str("command", o.command);
  j.num("voxels", static_cast<double>(nv));
  j.num("neighbours_per_voxel", static_cast<double>(s.graph().edge_count()) / nv);
  j.num("species", static_cast<double>(m.species.size()));
  j.num("molecules_per_species", static_cast<double>(molecules));
  j.num("events", static_cast<double>(fired));
  j.num("cpu_s", cpu);
  j.num("ns_per_event", ns_event);
  j.num("events_per_s", 1e9 / ns_event);
  j.num("graph_build_ns_per_voxel", 1e9 * build_s / nv);
  j.num("restart_ns_per_voxel", 1e9 * restart_s / nv);
  j.num("direct_baseline_events", static_cast<double>(dfired));
  j.num("direct_baseline_ns_per_event", d_ns);
  j.num("speedup_vs_direct", d_ns / ns_event);
  j.num("target_ns_per_event", target);
  j.str("urdme_ns_per_event", o.scenario == "b" ? "336-402" : std::to_string(int(urdme)));
  j.str("urdme_restart_ns_per_voxel", "45-121");
  char line[512];
  std::snprintf(line, sizeof line,
                "ssa_bench %s: %.0f events in %.3f s thread CPU: %.1f ns/event (target <= %.0f, "
                "URDME %s), %.3g events/s, restart %.1f ns/voxel, graph build %.1f ns/voxel, "
                "direct baseline %.3g ns/event (%llu events) -> speed-up %.0fx, peak RSS %.0f MiB",
                o.scenario.c_str(), double(fired), cpu, ns_event, target,
                o.scenario == "b" ? "336-402" : std::to_string(int(urdme)).c_str(), 1e9 / ns_event,
                1e9 * restart_s / nv, 1e9 * build_s / nv, d_ns,
                static_cast<unsigned long long>(dfired), d_ns / ns_event, peak_rss_mib());
  emit(j, line);
  return 0;
}

int sph_scenario(const Options& o) {
  const int n = o.n > 0 ? o.n : 200;  // --n 100: the 1e4-particle coupled case
  const double dx = 1.0, h = 3.0 * dx;
  Model m;
  m.box.dimension = 2;
  for (int a = 0; a < 3; ++a) {
    m.box.lo[a] = 0;
    m.box.hi[a] = a < 2 ? n * dx : 1.0;
    m.box.periodic[a] = a < 2;
  }
  m.smoothing_length = h;
  m.species = {{"A", 0.05}};
  ParticleState p = lattice(2, n, dx, 0.2, 3);
  const std::size_t nv = p.size();
  NsmSolver s(m, 777);
  s.update_graph(p);
  s.set_counts(0, scatter(nv, static_cast<std::int64_t>(nv) * 3, 4));
  const double a0 = total_rate(s);
  const double tau = static_cast<double>(nv) / a0;  // ~1 event per voxel per step
  std::mt19937_64 gen(5);
  std::normal_distribution<double> g(0.0, o.move * dx);
  const int steps = 40;
  // The rebuild may use OpenMP threads (GraphBuilder): wall time, CPU time of all
  // threads (process clock) and of the calling thread, so neither hides the other.
  double rebuild_cpu = 0, rebuild_wall = 0, rebuild_proc = 0, event_cpu = 0;
  std::uint64_t fired_total = 0;
  for (int step = 0; step < steps; ++step) {
    for (std::size_t i = 0; i < nv; ++i) {  // small displacements: a flowing fluid
      for (int a = 0; a < 2; ++a) {
        double& x = p.positions[3 * i + a];
        x += g(gen);
        if (x < 0) x += n * dx;
        if (x >= n * dx) x -= n * dx;
      }
    }
    const double w0 = wall_s(), p0 = process_cpu_s(), t0 = thread_cpu_s();
    s.update_graph(p);
    rebuild_cpu += thread_cpu_s() - t0;
    rebuild_proc += process_cpu_s() - p0;
    rebuild_wall += wall_s() - w0;
    std::uint64_t fired = 0;
    event_cpu += run_events(s, nv / tau, static_cast<double>(nv), fired);
    fired_total += fired;
  }
  // The graph builder alone (GraphBuilder::build, no rates or event queue) on the
  // same 40 position sets (same initial lattice and motion seed, replayed).
  double builder_wall = 0, builder_proc = 0;
  {
    ParticleState q = lattice(2, n, dx, 0.2, 3);
    std::mt19937_64 gen2(5);
    std::normal_distribution<double> g2(0.0, o.move * dx);
    GraphBuilder builder;
    DiffusionGraph graph;
    builder.build(graph, m, q);
    for (int step = 0; step < steps; ++step) {
      for (std::size_t i = 0; i < nv; ++i) {
        for (int a = 0; a < 2; ++a) {
          double& x = q.positions[3 * i + a];
          x += g2(gen2);
          if (x < 0) x += n * dx;
          if (x >= n * dx) x -= n * dx;
        }
      }
      const double w0 = wall_s(), p0 = process_cpu_s();
      builder.build(graph, m, q);
      builder_proc += process_cpu_s() - p0;
      builder_wall += wall_s() - w0;
    }
  }
  // Read floor: the least a rebuild must do per candidate pair, one thread: load the
  // target, its coordinates, mass and density and fold them into one number per
  // voxel (no minimum image, filter, weight or output). The candidates are the pairs
  // within h (1 + skin) of the final positions, as the builder's list.
  double floor_cpu = 1e30;
  std::size_t floor_pairs = 0;
  {
    const NeighborList nl =
        build_neighbor_list(m.box, p.positions, h * (1.0 + GraphBuilder::kSkinFraction));
    floor_pairs = nl.col.size();
    std::vector<double> acc(nv);
    for (int rep = 0; rep < 20; ++rep) {
      const double t0 = thread_cpu_s();
      for (std::size_t i = 0; i < nv; ++i) {
        const double xi = p.positions[3 * i], yi = p.positions[3 * i + 1];
        double a = 0;
        for (std::uint32_t k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k) {
          const std::uint32_t jj = nl.col[k];
          const double ddx = xi - p.positions[3 * jj], ddy = yi - p.positions[3 * jj + 1];
          a += (ddx * ddx + ddy * ddy) * p.masses[jj] * p.densities[jj];
        }
        acc[i] = a;
      }
      floor_cpu = std::min(floor_cpu, thread_cpu_s() - t0);
      if (acc[rep % nv] < 0) std::printf("impossible\n");  // keeps the loop
    }
  }
  // Baseline on the same final graph.
  DirectSolver d(m, 777);
  d.update_graph(p);
  d.set_counts(0, std::vector<std::int64_t>(s.counts(0).begin(), s.counts(0).end()));
  std::uint64_t dfired = 0;
  const double dcpu = run_events(d, a0, o.baseline_events / 10, dfired);
  const double d_ns = 1e9 * dcpu / static_cast<double>(std::max<std::uint64_t>(dfired, 1));
  const double ns_event = 1e9 * event_cpu / static_cast<double>(fired_total);
  const double per = 1e9 / (static_cast<double>(steps) * nv);  // s -> ns/voxel/step
  const double rebuild_ns = per * rebuild_wall;
  const double step_ns = per * (rebuild_wall + event_cpu);  // the event loop is serial
  const int threads = s.state().graph_builder().threads();
  Json j;
  j.str("scenario", "d");
  j.str("command", o.command);
  j.num("voxels", static_cast<double>(nv));
  j.num("neighbours_per_voxel", static_cast<double>(s.graph().edge_count()) / nv);
  j.num("steps", steps);
  j.num("move_dx_per_axis_per_step", o.move);
  j.num("events", static_cast<double>(fired_total));
  j.num("events_per_voxel_per_step", static_cast<double>(fired_total) / (steps * nv));
  j.num("event_cpu_s", event_cpu);
  j.num("rebuild_cpu_s", rebuild_cpu);
  j.num("ns_per_event", ns_event);
  j.num("events_per_s", 1e9 / ns_event);
  j.num("rebuild_threads", threads);
  j.num("rebuild_ns_per_voxel", rebuild_ns);  // wall
  j.num("rebuild_cpu_ns_per_voxel", per * rebuild_proc);
  j.num("rebuild_thread_cpu_ns_per_voxel", per * rebuild_cpu);
  j.num("graph_builder_ns_per_voxel", per * builder_wall);  // wall, builder alone
  j.num("graph_builder_cpu_ns_per_voxel", per * builder_proc);
  j.num("neighbour_searches", static_cast<double>(s.state().graph_builder().searches()));
  j.num("candidates_per_voxel",
        static_cast<double>(s.state().graph_builder().candidate_count()) / nv);
  j.num("coupled_step_ns_per_voxel", step_ns);
  j.num("read_floor_pairs_per_voxel", static_cast<double>(floor_pairs) / nv);
  j.num("read_floor_cpu_ns_per_voxel", 1e9 * floor_cpu / nv);  // one thread, min of 20
  j.num("direct_baseline_events", static_cast<double>(dfired));
  j.num("direct_baseline_ns_per_event", d_ns);
  j.num("speedup_vs_direct", d_ns / ns_event);
  char line[1024];
  std::snprintf(line, sizeof line,
                "ssa_bench d: %d steps x %zu voxels, %.2f events/voxel/step: %.1f ns/event, "
                "rebuild (cell list + graph + rates + heap) %.1f ns/voxel wall on %d threads "
                "(CPU %.1f all threads, %.1f calling thread; graph builder alone %.1f wall, %.1f "
                "CPU), %.0f searches, whole step %.1f "
                "ns/voxel, read floor %.1f ns/voxel on one thread (%.1f pairs), direct baseline "
                "%.3g ns/event -> speed-up %.0fx, peak RSS %.0f MiB",
                steps, nv, static_cast<double>(fired_total) / (steps * nv), ns_event, rebuild_ns,
                threads, per * rebuild_proc, per * rebuild_cpu, per * builder_wall,
                per * builder_proc, static_cast<double>(s.state().graph_builder().searches()),
                step_ns, 1e9 * floor_cpu / nv, static_cast<double>(floor_pairs) / nv, d_ns,
                d_ns / ns_event, peak_rss_mib());
  emit(j, line);
  return 0;
}

int boost_scenario(const Options& o) {
  const int n = 32;
  const Model m = lattice_model(3, n, 1.2, false);
  const ParticleState p = lattice(3, n, 1.0, 0.0, 1);
  double t0 = thread_cpu_s();
  const DiffusionGraph g = DiffusionGraph::build(m, p);
  const double own_build = thread_cpu_s() - t0;
  const std::size_t nv = g.size();
  // Boost CSR from the same (row-sorted) edge list, weights as a bundled property.
  struct EdgeW {
    double w;
  };
  using Csr = boost::compressed_sparse_row_graph<boost::directedS, boost::no_property, EdgeW,
                                                 boost::no_property, std::uint32_t, std::uint32_t>;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  std::vector<EdgeW> props;
  edges.reserve(g.edge_count());
  for (std::uint32_t i = 0; i < nv; ++i) {
    for (auto k = g.row_start[i]; k < g.row_start[i + 1]; ++k) {
      edges.emplace_back(i, g.edges[k].target);
      props.push_back({g.edges[k].weight});
    }
  }
  t0 = thread_cpu_s();
  Csr bg(boost::edges_are_sorted, edges.begin(), edges.end(), props.begin(), nv);
  const double boost_build = thread_cpu_s() - t0;
  // Traversal in the access pattern of event selection: random voxel, scan its out-edges.
  const int queries = 20000000;
  std::mt19937_64 gen(1);
  std::vector<std::uint32_t> vox(1 << 16);
  for (auto& v : vox) v = static_cast<std::uint32_t>(gen() % nv);
  double acc_own = 0, acc_boost = 0;
  t0 = thread_cpu_s();
  for (int q = 0; q < queries; ++q) {
    const std::uint32_t i = vox[q & 0xFFFF];
    for (auto k = g.row_start[i]; k < g.row_start[i + 1]; ++k)
      acc_own += g.edges[k].weight * g.edges[k].target;
  }
  const double own_scan = thread_cpu_s() - t0;
  t0 = thread_cpu_s();
  for (int q = 0; q < queries; ++q) {
    const std::uint32_t i = vox[q & 0xFFFF];
    auto [it, end] = boost::out_edges(i, bg);
    for (; it != end; ++it) acc_boost += bg[*it].w * boost::target(*it, bg);
  }
  const double boost_scan = thread_cpu_s() - t0;
  Json j;
  j.str("scenario", "boost_csr");
  j.str("command", o.command);
  j.num("voxels", static_cast<double>(nv));
  j.num("edges", static_cast<double>(g.edge_count()));
  j.num("own_graph_build_ns_per_voxel", 1e9 * own_build / nv);
  j.num("boost_csr_construct_from_sorted_edges_ns_per_voxel", 1e9 * boost_build / nv);
  j.num("own_row_scan_ns", 1e9 * own_scan / queries);
  j.num("boost_row_scan_ns", 1e9 * boost_scan / queries);
  j.num("checksum_equal", acc_own == acc_boost ? 1 : 0);
  char line[512];
  std::snprintf(line, sizeof line,
                "ssa_bench boost_csr: row scan own %.2f ns vs Boost %.2f ns; Boost construction "
                "adds %.1f ns/voxel on top of our whole graph build (%.1f ns/voxel)",
                1e9 * own_scan / queries, 1e9 * boost_scan / queries, 1e9 * boost_build / nv,
                1e9 * own_build / nv);
  emit(j, line);
  return acc_own == acc_boost ? 0 : 1;
}

}  // namespace
}  // namespace sadr::ssa::bench

int main(int argc, char** argv) {
  using namespace sadr::ssa::bench;
  Options o;
  for (int k = 0; k < argc; ++k) {
    if (k) o.command.push_back(' ');
    o.command.append(argv[k]);
  }
  for (int k = 1; k < argc; ++k) {
    const std::string a = argv[k];
    if (a == "--events" && k + 1 < argc) {
      o.events = std::atof(argv[++k]);
    } else if (a == "--n" && k + 1 < argc) {
      o.n = std::atoi(argv[++k]);
    } else if (a == "--move" && k + 1 < argc) {
      o.move = std::atof(argv[++k]);
    } else if (a == "--baseline-events" && k + 1 < argc) {
      o.baseline_events = std::atof(argv[++k]);
    } else {
      o.scenario = a;
    }
  }
  if (o.scenario == "a" || o.scenario == "b" || o.scenario == "c") return lattice_scenario(o);
  if (o.scenario == "d") return sph_scenario(o);
  if (o.scenario == "boost_csr") return boost_scenario(o);
  std::fprintf(stderr, "unknown scenario '%s' (a | b | c | d | boost_csr)\n", o.scenario.c_str());
  return 2;
}
