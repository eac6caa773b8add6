// SPDX-License-Identifier: MIT
/// \file backend_contract_scene.hpp
/// The scene of the backend contract (backend_contract_test.cpp, run on every registered
/// backend): a 3D periodic box of jittered lattice particles (N >= kMinParallel so threads
/// really run), k_B T > 0 where the backend has thermal noise, one deterministic species with a
/// step profile. BackendCase holds the scene's knobs; the tDPD property tests reuse it.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "sadr/common/rng.hpp"
#include "sadr/fluid/fluid_backend.hpp"
#ifdef _OPENMP
#include <omp.h>
#endif

namespace sadr::fluid::generic_test {

struct BackendCase {
  std::string name;
  std::function<std::unique_ptr<FluidBackend>()> make;
  double smoothing_length = 1.58;  ///< [length]
  double number_density = 4.0;     ///< particles per unit volume
  double reference_density = 4.0;  ///< FluidModel::reference_density
  double particle_mass = 1.0;      ///< mass given in the initial state
  double sound_speed = 4.0;
  double shear_viscosity = 1.0;
  double temperature = 1.0;
  double diffusivity = 0.1;
  double time_step = 0.01;  ///< per advance() call
  int steps = 5;
};
inline std::string case_name(const ::testing::TestParamInfo<BackendCase>& info) {
  return info.param.name;
}
/// How GoogleTest prints a case (its name, not its bytes).
inline void PrintTo(const BackendCase& c, std::ostream* os) {
  *os << c.name;
}

struct Scene {
  FluidModel model;
  ParticleState state;
  std::vector<std::vector<double>> conc;
};

/// Jittered cubic lattice in a periodic cube of side ~ (n_target / rho)^(1/3), n >= 1100.
inline Scene make_scene(const BackendCase& bc, std::uint64_t seed) {
  Scene s;
  const int per_axis = 11;  // 1331 particles
  const double spacing = std::cbrt(1.0 / bc.number_density);
  const double len = per_axis * spacing;
  s.model.box.dimension = 3;
  s.model.box.lo = {0, 0, 0};
  s.model.box.hi = {len, len, len};
  s.model.box.periodic = {true, true, true};
  s.model.smoothing_length = bc.smoothing_length;
  s.model.reference_density = bc.reference_density;
  s.model.sound_speed = bc.sound_speed;
  s.model.shear_viscosity = bc.shear_viscosity;
  s.model.temperature = bc.temperature;
  s.model.seed = seed;
  SpeciesSpec sp;
  sp.def.name = "A";
  sp.def.diffusivity = bc.diffusivity;
  s.model.species.push_back(sp);
  const std::size_t n = static_cast<std::size_t>(per_axis * per_axis * per_axis);
  s.state.dimension = 3;
  s.state.resize(n, true);
  const rng::CounterRng jitter{12345};
  std::vector<double> c(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t ix = i % per_axis, iy = (i / per_axis) % per_axis,
                      iz = i / (per_axis * per_axis);
    const auto u = jitter.uniform2(rng::Purpose::kTest, 0, static_cast<std::uint32_t>(i), 0);
    const auto w = jitter.uniform2(rng::Purpose::kTest, 1, static_cast<std::uint32_t>(i), 0);
    s.state.positions[3 * i] = (ix + 0.5 + 0.3 * (u[0] - 0.5)) * spacing;
    s.state.positions[3 * i + 1] = (iy + 0.5 + 0.3 * (u[1] - 0.5)) * spacing;
    s.state.positions[3 * i + 2] = (iz + 0.5 + 0.3 * (w[0] - 0.5)) * spacing;
    for (int a = 0; a < 3; ++a) s.state.velocities[3 * i + a] = 0.0;
    s.state.densities[i] = bc.reference_density;
    s.state.masses[i] = bc.particle_mass;
    c[i] = ix < per_axis / 2 ? 1.0 : 0.0;
  }
  s.conc.push_back(c);
  return s;
}

}  // namespace sadr::fluid::generic_test
