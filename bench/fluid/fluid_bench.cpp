// SPDX-License-Identifier: MIT
/// \file fluid_bench.cpp
/// Macro benchmark of the SDPD backend (issue 4): particle-steps per CPU-second for a periodic
/// box at rest with thermal noise, h = 3 dx, 1e4 and 1e5 particles, 3D and 2D, one thread and
/// all threads; the extra cost per deterministic species; memory per particle.
/// Prints one JSON document, then one summary line. `--quick` runs only the 1e4 cases.
/// One "particle-step" is one particle advanced by one full predictor-corrector step, which
/// costs TWO force evaluations (LAMMPS' Verlet costs one); both figures are printed.
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "fluid_bench_case.hpp"
#include "sadr/common/openmp_env.hpp"
#include "sdpd/sdpd_backend.hpp"
#ifdef SADR_HAVE_OPENMP
#include <omp.h>
#endif

namespace {

using sadr::fluid::FluidModel;
using sadr::fluid::SdpdBackend;

double cpu_seconds() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return static_cast<double>(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
}

struct Result {
  int dim;
  long n;
  int threads;
  int species;
  double steps;
  double neighbours;
  double ps_per_cpu_s;
  double ps_per_wall_s;
  double bytes_per_particle;
  double list_builds;  ///< neighbour-list builds in the timed steps
};

// FNV-1a over the bytes of the state: compares trajectories of two builds bit for bit.
std::uint64_t state_hash(const SdpdBackend& b) {
  sadr::ParticleState s;
  b.read_state(s);
  std::uint64_t h = 1469598103934665603ULL;
  auto mix = [&h](const std::vector<double>& v) {
    const auto* p = reinterpret_cast<const unsigned char*>(v.data());
    for (std::size_t k = 0; k < v.size() * sizeof(double); ++k) h = (h ^ p[k]) * 1099511628211ULL;
  };
  mix(s.positions);
  mix(s.velocities);
  mix(s.densities);
  return h;
}

Result run_case(int dim, long n_target, int threads, int species, int steps,
                std::uint64_t* hash = nullptr) {
#ifdef SADR_HAVE_OPENMP
  omp_set_num_threads(threads);
#else
  threads = 1;
#endif
  FluidModel m;
  sadr::ParticleState p = sadr::fluid::bench::bench_case(dim, n_target, m);
  if (const char* e = std::getenv("SADR_BENCH_NOISE")) {  // diagnostics: off | uniform
    if (std::strcmp(e, "off") == 0) m.temperature = 0.0;
    if (std::strcmp(e, "uniform") == 0) m.noise = sadr::fluid::NoiseDistribution::kUniform;
  }
  std::vector<std::vector<double>> c;
  for (int s = 0; s < species; ++s) {
    std::string name = "S";
    name += std::to_string(s);
    m.species.push_back({name, 0.1, true, {}, {}});
    c.emplace_back(p.size(), 1.0 + s);
  }
  SdpdBackend b;
  b.initialize(m, p, c);
  const double dt = 0.02;  // below every limit: one sub-step per advance()
  b.advance(0, dt);        // warm-up (builds the neighbour list)
  const double bytes = static_cast<double>(b.memory_bytes());
  const auto builds0 = b.list_builds();
  const double t_cpu0 = cpu_seconds();
  const auto t_wall0 = std::chrono::steady_clock::now();
  std::uint32_t substeps = 0;
  for (int s = 1; s <= steps; ++s)
    substeps += b.advance(static_cast<std::uint64_t>(s), dt).substeps;
  const double cpu = cpu_seconds() - t_cpu0;
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t_wall0).count();
  if (hash) {
    *hash = state_hash(b);
    for (int k = 0; k < species; ++k) {
      for (double v : b.concentrations(k))
        *hash ^= std::hash<double>{}(v) + 0x9e3779b9U + (*hash << 6);
    }
  }
  const double np = static_cast<double>(p.size());
  // mean neighbour count within h (lattice: same for every particle)
  double nb = 0;
  {
    const double h2 = 9.0;
    const std::size_t i = p.size() / 2;
    for (std::size_t j = 0; j < p.size(); ++j) {
      double d[3];
      for (int a = 0; a < 3; ++a) d[a] = p.positions[3 * i + a] - p.positions[3 * j + a];
      sadr::fluid::PeriodicBox(m.box).minimum_image(d);
      const double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
      if (j != i && r2 < h2) nb += 1;
    }
  }
  return {dim,
          static_cast<long>(p.size()),
          threads,
          species,
          static_cast<double>(substeps),
          nb,
          np * substeps / cpu,
          np * substeps / wall,
          bytes / np,
          static_cast<double>(b.list_builds() - builds0)};
}

}  // namespace

int main(int argc, char** argv) {
  // the product's default: OMP_WAIT_POLICY=passive unless OMP_WAIT_POLICY or GOMP_SPINCOUNT is set
  sadr::ensure_passive_openmp_wait(argv);
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  if (argc > 1 &&
      std::strcmp(argv[1], "--one") == 0) {  // diagnostics: one 3D 1e4 single-thread case
    const Result r = run_case(3, 10000, 1, 0, 10);
    std::printf("3D 1e4 1 thread: %.4g particle-steps/CPU-s\n", r.ps_per_cpu_s);
    return 0;
  }
  if (argc > 5 && std::strcmp(argv[1], "--case") == 0) {  // diagnostics: --case D N threads steps
    const Result r =
        run_case(std::atoi(argv[2]), std::atol(argv[3]), std::atoi(argv[4]), 0, std::atoi(argv[5]));
    std::printf("%dD %ld %d thread(s): %.4g particle-steps/CPU-s, %.4g /wall-s, %.0f list builds\n",
                r.dim, r.n, r.threads, r.ps_per_cpu_s, r.ps_per_wall_s, r.list_builds);
    return 0;
  }
  if (argc > 1 && std::strcmp(argv[1], "--hash") == 0) {
    // diagnostics: state hashes after a few steps (3D/2D, with and without a species), to show
    // that an optimisation leaves the trajectory bit-identical (SADR_BENCH_NOISE applies).
    // `--hash T S` runs S steps (default 5) on T threads (the hashes must not depend on T).
    const int threads = argc > 2 ? std::max(1, std::atoi(argv[2])) : 1;
    const int steps = argc > 3 ? std::max(1, std::atoi(argv[3])) : 5;
    for (int dim : {3, 2}) {
      for (int species : {0, 1}) {
        std::uint64_t h = 0;
        run_case(dim, dim == 3 ? 8000 : 10000, threads, species, steps, &h);
        std::printf("%dD species %d: %016llx\n", dim, species, static_cast<unsigned long long>(h));
      }
    }
    return 0;
  }
  int max_threads = 1;
#ifdef SADR_HAVE_OPENMP
  max_threads = omp_get_max_threads();
#endif
  std::vector<Result> rs;
  for (long n : {10000L, 100000L}) {
    if (quick && n > 10000) continue;
    for (int dim : {3, 2}) {
      const int steps = n > 10000 ? (dim == 3 ? 3 : 10) : (dim == 3 ? 10 : 40);
      for (int th : {1, max_threads}) {
        rs.push_back(run_case(dim, n, th, 0, steps));
        if (max_threads == 1) break;
      }
    }
  }
  // extra cost per deterministic species (2D, 1e4, one thread)
  // (0 -> 4 species also switches from the half-pair path to the full-list gather, which a
  // transported species needs; 1 -> 4 species is the cost of a species on the gather path)
  const Result s0 = run_case(2, 10000, 1, 0, 40), s4 = run_case(2, 10000, 1, 4, 40);
  const Result s1 = run_case(2, 10000, 1, 1, 40);
  const double per_species =
      (1.0 / s4.ps_per_cpu_s - 1.0 / s0.ps_per_cpu_s) / 4.0 / (1.0 / s0.ps_per_cpu_s);
  const double per_species_gather =
      (1.0 / s4.ps_per_cpu_s - 1.0 / s1.ps_per_cpu_s) / 3.0 / (1.0 / s1.ps_per_cpu_s);
  const double lammps3d = 113e3, lammps2d = 460e3;
  std::printf(
      "{\n  \"benchmark\": \"fluid_sdpd_periodic_box_thermal_noise\",\n  \"h_over_dx\": 3,\n");
  std::printf(
      "  \"lammps_sdpd_taitwater_isothermal_particle_steps_per_cpu_s\": {\"3d\": %.0f, \"2d\": "
      "%.0f},\n",
      lammps3d, lammps2d);
  std::printf(
      "  \"note\": \"one particle-step = one predictor-corrector step = 2 force evaluations; "
      "LAMMPS: 1\",\n");
  std::printf("  \"cases\": [\n");
  for (std::size_t k = 0; k < rs.size(); ++k) {
    const auto& r = rs[k];
    const double lammps = r.dim == 3 ? lammps3d : lammps2d;
    std::printf(
        "    {\"dim\": %d, \"particles\": %ld, \"threads\": %d, \"neighbours\": %.0f, \"steps\": "
        "%.0f, "
        "\"particle_steps_per_cpu_s\": %.4g, \"particle_steps_per_wall_s\": %.4g, "
        "\"force_evaluations_per_cpu_s\": %.4g, \"ratio_vs_lammps_per_cpu\": %.3f, "
        "\"bytes_per_particle\": %.0f, \"list_builds\": %.0f}%s\n",
        r.dim, r.n, r.threads, r.neighbours, r.steps, r.ps_per_cpu_s, r.ps_per_wall_s,
        2 * r.ps_per_cpu_s, r.ps_per_cpu_s / lammps, r.bytes_per_particle, r.list_builds,
        k + 1 < rs.size() ? "," : "");
  }
  std::printf(
      "  ],\n  \"extra_cost_per_deterministic_species_fraction\": %.4f,\n"
      "  \"extra_cost_per_species_on_gather_path_fraction\": %.4f,\n"
      "  \"species_note\": \"0 -> 4 species includes the switch from the half-pair path to the "
      "full-list gather (transported species); the second figure is 1 -> 4 species\"\n}\n",
      per_species, per_species_gather);
  const Result* r3 = nullptr;
  const Result* r2 = nullptr;
  for (const auto& r : rs) {
    if (r.threads == 1 && r.n >= 90000 && r.dim == 3) r3 = &r;
    if (r.threads == 1 && r.n >= 90000 && r.dim == 2) r2 = &r;
  }
  if (!r3) r3 = &rs[0];
  if (!r2) r2 = &rs[rs.size() - 1];
  std::printf(
      "fluid_bench: 3D %.3g particle-steps/CPU-s (%.2fx LAMMPS), 2D %.3g (%.2fx LAMMPS), +%.1f%% "
      "per species\n",
      r3->ps_per_cpu_s, r3->ps_per_cpu_s / lammps3d, r2->ps_per_cpu_s, r2->ps_per_cpu_s / lammps2d,
      100 * per_species);
  return 0;
}
