// SPDX-License-Identifier: MIT
/// \file tdpd_bench.cpp
/// tDPD throughput: particle-steps per CPU-second (std::clock, all threads summed, so the
/// figure is per core) at rho = 4, r_c = r_cc = 1.58, k_B T = 1, dt = 0.01, for ~1e4 and ~1e5
/// particles and 1, 4, 25 species, next to LAMMPS `pair tdpd` measured on this machine
/// (233k particle-steps/CPU-s with 1 species, 112k with 4).
/// Usage: fluid_tdpd_bench [out.json] [--quick] [--small|--large] [--uniform] [--skin S]
///   [--steps K] [--species N]  (OMP_NUM_THREADS=1)
///   --quick: 5 timed steps; --small / --large: only the ~1e4- / ~1e5-particle configurations;
///   --uniform: FluidModel::noise = kUniform (uniform pair noise of unit variance);
///   --skin S: tdpd.skin (Verlet skin / r_c; default: the backend's); --steps K: warm-up steps
///   before timing (default 20; more steps let the particles mix, as in a long run);
///   --species N: only the N-species runs (bench/peers/side_by_side.py --memory: 1 species).
#include <cmath>
#include <cstdio>
#include <ctime>
#include <string>
#include <vector>

#include "sadr/common/rng.hpp"
#include "tdpd/tdpd_backend.hpp"

namespace {

struct Result {
  std::size_t particles;
  int species;
  int steps;
  double cpu_s;
  double wall_s;
  double rate;                ///< particle-steps per CPU-second
  std::uint64_t list_builds;  ///< neighbour-list builds in the timed steps
};

Result run(int per_axis, int nspecies, int steps, bool uniform, double skin, int warmup) {
  using namespace sadr;
  using namespace sadr::fluid;
  const double a = std::cbrt(0.25);
  const double len = per_axis * a;
  FluidModel m;
  m.box.dimension = 3;
  m.box.hi = {len, len, len};
  m.box.periodic = {true, true, true};
  m.smoothing_length = 1.58;
  m.reference_density = 4.0;
  m.temperature = 1.0;
  m.seed = 1;
  if (uniform) m.noise = NoiseDistribution::kUniform;
  if (skin > 0.0) m.backend_parameters["skin"] = skin;
  for (int s = 0; s < nspecies; ++s) {
    SpeciesSpec sp;
    char name[16];  // not "S" + to_string(s): GCC 12 -O1+ASan warns -Wrestrict (false positive)
    std::snprintf(name, sizeof name, "S%d", s);
    sp.def.name = name;
    sp.def.diffusivity = 0.5;  // kappa
    m.species.push_back(sp);
  }
  const std::size_t n = static_cast<std::size_t>(per_axis) * per_axis * per_axis;
  ParticleState st;
  st.dimension = 3;
  st.resize(n, true);
  const rng::CounterRng jit{3};
  std::vector<std::vector<double>> conc(nspecies, std::vector<double>(n));
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t c[3] = {i % per_axis, (i / per_axis) % per_axis, i / (per_axis * per_axis)};
    const auto u = jit.uniform2(rng::Purpose::kTest, 0, static_cast<std::uint32_t>(i), 0);
    const auto w = jit.uniform2(rng::Purpose::kTest, 1, static_cast<std::uint32_t>(i), 0);
    const double j3[3] = {u[0], u[1], w[0]};
    for (int k = 0; k < 3; ++k) {
      st.positions[3 * i + k] = (static_cast<double>(c[k]) + 0.2 + 0.6 * j3[k]) * a;
      st.velocities[3 * i + k] = 0.0;
    }
    st.densities[i] = 4.0;
    st.masses[i] = 1.0;
    for (int s = 0; s < nspecies; ++s) conc[s][i] = (c[0] + s) % 2 ? 1.0 : 0.0;
  }
  TdpdBackend b;
  b.initialize(m, st, conc);
  std::uint64_t step = 0;
  for (; step < static_cast<std::uint64_t>(warmup); ++step) b.advance(step, 0.01);  // thermalise
  const std::uint64_t builds0 = b.list_builds();
  const std::clock_t c0 = std::clock();
  timespec w0{}, w1{};
  std::timespec_get(&w0, TIME_UTC);
  for (int k = 0; k < steps; ++k) b.advance(step++, 0.01);
  std::timespec_get(&w1, TIME_UTC);
  const double cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
  const double wall = static_cast<double>(w1.tv_sec - w0.tv_sec) +
                      1e-9 * static_cast<double>(w1.tv_nsec - w0.tv_nsec);
  return {n,
          nspecies,
          steps,
          cpu,
          wall,
          static_cast<double>(n) * steps / cpu,
          b.list_builds() - builds0};
}

}  // namespace

int main(int argc, char** argv) {
  std::string out = "tdpd_bench.json";
  bool quick = false;
  bool small_only = false;
  bool large_only = false;
  bool uniform = false;
  double skin = 0.0;
  int warmup = 20;
  int only_species = 0;  // 0: all of 1, 4, 25
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--quick") {
      quick = true;
    } else if (arg == "--small") {
      small_only = true;
    } else if (arg == "--large") {
      large_only = true;
    } else if (arg == "--uniform") {
      uniform = true;
    } else if (arg == "--skin" && i + 1 < argc) {
      skin = std::stod(argv[++i]);
    } else if (arg == "--steps" && i + 1 < argc) {
      warmup = std::stoi(argv[++i]);
    } else if (arg == "--species" && i + 1 < argc) {
      only_species = std::stoi(argv[++i]);
    } else {
      out = arg;
    }
  }
  const double lammps[2] = {233e3, 112e3};  // 1 and 4 species, this machine
  std::vector<Result> res;
  for (const int per_axis : {22, 46}) {  // 10648 and 97336 particles
    if ((small_only && per_axis > 22) || (large_only && per_axis == 22)) continue;
    for (const int ns : {1, 4, 25}) {
      if (only_species > 0 && ns != only_species) continue;
      const int steps = quick ? 5 : (per_axis == 22 ? 100 : 20);
      res.push_back(run(per_axis, ns, steps, uniform, skin, warmup));
      const auto& r = res.back();
      const double ref = ns == 1 ? lammps[0] : ns == 4 ? lammps[1] : 0.0;
      std::printf(
          "N=%zu species=%d: %.0f particle-steps/CPU-s (LAMMPS pair tdpd: %s) cpu %.2fs wall "
          "%.2fs, %llu list builds in %d steps\n",
          r.particles, ns, r.rate,
          ref > 0 ? (std::to_string(static_cast<int>(ref / 1e3)) + "k").c_str() : "n/a", r.cpu_s,
          r.wall_s, static_cast<unsigned long long>(r.list_builds), r.steps);
    }
  }
  FILE* f = std::fopen(out.c_str(), "w");
  if (!f) {
    std::perror(out.c_str());
    return 1;
  }
  std::fprintf(f,
               "{\n  \"benchmark\": \"tdpd\",\n  \"units\": \"particle-steps per CPU-second\",\n"
               "  \"noise\": \"%s\",\n  \"skin\": %g,\n  \"warmup_steps\": %d,\n",
               uniform ? "uniform" : "gaussian", skin, warmup);
  std::fprintf(
      f, "  \"lammps_pair_tdpd\": {\"species_1\": %.0f, \"species_4\": %.0f},\n  \"runs\": [\n",
      lammps[0], lammps[1]);
  for (std::size_t k = 0; k < res.size(); ++k) {
    const auto& r = res[k];
    std::fprintf(f,
                 "    {\"particles\": %zu, \"species\": %d, \"steps\": %d, \"cpu_s\": %.4f, "
                 "\"wall_s\": %.4f, \"rate\": %.1f, \"list_builds\": %llu}%s\n",
                 r.particles, r.species, r.steps, r.cpu_s, r.wall_s, r.rate,
                 static_cast<unsigned long long>(r.list_builds), k + 1 < res.size() ? "," : "");
  }
  std::fprintf(f, "  ]\n}\n");
  std::fclose(f);
  return 0;
}
