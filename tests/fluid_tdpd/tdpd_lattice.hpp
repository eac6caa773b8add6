// SPDX-License-Identifier: MIT
/// \file tdpd_lattice.hpp
/// The jittered start lattice of the tDPD validation tests: nx x ny x nz cells of `spacing`
/// (4^(-1/3) gives number density 4), one particle per cell placed uniformly in the middle
/// 60 % of it per axis (CounterRng kInitialCondition sub-draws 0 and 1), and with `thermal`
/// velocities N(0, 1) per axis (sub-draws 2 and 3), else 0. Densities and masses are left
/// to the caller.
#pragma once

#include <cstddef>
#include <cstdint>

#include "sadr/common/particle_state.hpp"
#include "sadr/common/rng.hpp"

namespace sadr::fluid::test {

inline void fill_jittered_lattice(ParticleState& state, int nx, int ny, int nz, double spacing,
                                  std::uint64_t seed, bool thermal) {
  const std::size_t n = static_cast<std::size_t>(nx) * ny * nz;
  state.dimension = 3;
  state.resize(n, true);
  const rng::CounterRng rng{seed};
  constexpr auto kInit = rng::Purpose::kInitialCondition;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t c[3] = {i % nx, (i / nx) % ny, i / (static_cast<std::size_t>(nx) * ny)};
    const auto id = static_cast<std::uint32_t>(i);
    const auto u = rng.uniform2(kInit, 0, id, 0);
    const auto w = rng.uniform2(kInit, 1, id, 0);
    const double jj[3] = {u[0], u[1], w[0]};
    double vv[3] = {0.0, 0.0, 0.0};
    if (thermal) {
      const auto g1 = rng.normal2(kInit, 2, id, 0);
      const auto g2 = rng.normal2(kInit, 3, id, 0);
      vv[0] = g1[0], vv[1] = g1[1], vv[2] = g2[0];
    }
    for (int a = 0; a < 3; ++a) {
      state.positions[3 * i + a] = (static_cast<double>(c[a]) + 0.2 + 0.6 * jj[a]) * spacing;
      state.velocities[3 * i + a] = vv[a];
    }
  }
}

}  // namespace sadr::fluid::test
