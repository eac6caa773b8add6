// SPDX-License-Identifier: MIT
/// \file fluid_error_sweep.cpp
/// Run time versus error for Poiseuille start-up (SDPD, k_B T = 0) and the 1-D A + B
/// annihilation (deterministic species on frozen particles), over resolution x time step.
/// Prints CSV (case,resolution,dt,error,cpu_s,wall_s); make_error_table.py turns it into
/// docs/fluid-error-table.md.
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>

#include "fluid_test_scenes.hpp"
#include "reference_solutions.hpp"
#include "sdpd/sdpd_backend.hpp"
#include "static/static_backend.hpp"
#include "validation/line_scenes.hpp"

namespace {

using namespace sadr;
using namespace sadr::fluid;

double cpu_seconds() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return static_cast<double>(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
}

template <typename F>
void timed(const char* name, int res, double dt, F&& f) {
  const double c0 = cpu_seconds();
  const auto w0 = std::chrono::steady_clock::now();
  const double err = f();
  const double cpu = cpu_seconds() - c0;
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
  std::printf("%s,%d,%.4g,%.4e,%.3f,%.3f\n", name, res, dt, err, cpu, wall);
  std::fflush(stdout);
}

// Poiseuille start-up to t = 0.225 s (Morris walls), error = scaled L2 / u_max.
double poiseuille(int ny, double dt) {
  constexpr double kH = 1e-3, kNu = 1e-6, kRho = 1000.0, kG = 2e-4,
                   kUmax = kG * kH * kH / (8 * kNu);
  test::LatticeSpec ls;
  ls.dimension = 2;
  ls.n = {8, ny, 1};
  ls.dx = kH / ny;
  ls.periodic = {true, false, false};
  ls.wall_layers = 4;
  ls.rho0 = kRho;
  FluidModel m;
  const ParticleState p = test::make_lattice(ls, m.box);
  m.smoothing_length = 3.0 * ls.dx;
  m.reference_density = kRho;
  m.sound_speed = 40.0 * kUmax;
  m.shear_viscosity = kRho * kNu;
  m.gravity = {kG, 0, 0};
  m.max_time_step = dt;
  m.force_time_step = true;
  m.wall_model = WallModel::kMorrisExtrapolated;
  m.wall_regions = {{"bottom", {}, {-1, -1, -1}, {1, 0, 1}, {0, 1, 0}, {0, 0, 0}},
                    {"top", {}, {-1, kH, -1}, {1, 1, 1}, {0, -1, 0}, {0, kH, 0}}};
  SdpdBackend b;
  b.initialize(m, p, {});
  b.advance(0, 0.225);
  ParticleState s;
  b.read_state(s);
  std::vector<double> u, ref, w;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s.kind(i) == ParticleKind::kWall) continue;
    u.push_back(s.velocities[3 * i]);
    ref.push_back(test::poiseuille_exact(s.positions[3 * i + 1], b.time()));
    w.push_back(1.0);
  }
  return test::scaled_norms(u, ref, w, kUmax).first;
}

double poiseuille_viscous_limit(int ny) {
  const double dx = 1e-3 / ny, h = 3 * dx;
  return 0.125 * 0.25 * h * h / 1e-6;  // Morris viscous limit with h_M = h/2
}

// Annihilation, N_b = 1e3, t = 1 s, h = 1.8 dx, eps = 0: paper metric vs the PDE reference.
double annihilation(int np, double dt, const std::map<long, double>& ref) {
  const double dx = 1.0 / (np - 1), c0 = 1e3 * (np - 1);
  std::vector<double> xf, xw;
  for (int i = 1; i < np - 1; ++i) xf.push_back(i * dx);
  for (int m = 0; m < 3; ++m) {
    xw.push_back(-m * dx);
    xw.push_back(1.0 + m * dx);
  }
  const ParticleState p = test::make_line(xf, xw, dx);
  FluidModel model;
  model.box = test::line_box(-3 * dx, 1.0 + 3 * dx);
  model.smoothing_length = 1.8 * dx;
  model.diffusion_eps = 0.0;
  model.max_time_step = dt;
  model.force_time_step = true;
  model.wall_regions = {{"left", {}, {-1e9, 0, 0}, {0.5 * dx, 0, 0}, {1, 0, 0}, {0, 0, 0}},
                        {"right", {}, {1 - 0.5 * dx, 0, 0}, {1e9, 0, 0}, {-1, 0, 0}, {1, 0, 0}}};
  using T = WallCondition::Type;
  model.species = {{"A", 0.1, true, {}, {{T::kDirichlet, c0}, {T::kDirichlet, 0.0}}},
                   {"B", 0.1, true, {}, {{T::kDirichlet, 0.0}, {T::kDirichlet, c0}}}};
  model.reactions = {{"annihilation", {{0, 1}, {1, 1}}, {}, 0.1, {}, {}}};
  StaticBackend b;
  b.initialize(model, p, {});
  b.advance(0, 1.0);
  double s = 0;
  for (int i = 1; i < np - 1; ++i) {
    const double e = b.concentrations(0)[i - 1] / c0 - ref.at(static_cast<long>(np) * 1000 + i);
    s += e * e;
  }
  return std::sqrt(s) / (np - 1);
}

}  // namespace

int main() {
  std::printf("case,resolution,dt,error,cpu_s,wall_s\n");
  for (int ny : {10, 20, 40}) {
    const double lim = poiseuille_viscous_limit(ny);
    for (double f : {1.0, 0.5, 0.25}) {
      timed("poiseuille_t0.225_scaledL2", ny, f * lim, [&] { return poiseuille(ny, f * lim); });
    }
  }
  const auto cols = test::read_csv(test::refs_dir() + "/annihilation_1d_subset.csv");
  std::map<long, double> ref;  // key Np*1000 + i
  for (std::size_t k = 0; k < cols.at("Np").size(); ++k) {
    if (cols.at("Nb")[k] != 1e3 || std::fabs(cols.at("t")[k] - 1.0) > 1e-9) continue;
    const long np = std::lround(cols.at("Np")[k]);
    ref[np * 1000 + std::lround(cols.at("x")[k] * (np - 1))] = cols.at("uA")[k];
  }
  for (int np : {17, 33, 65}) {
    for (double dt : {1e-4, 5e-5, 2.5e-5}) {
      timed("annihilation_Nb1e3_t1_paper_metric", np, dt,
            [&] { return annihilation(np, dt, ref); });
    }
  }
  return 0;
}
