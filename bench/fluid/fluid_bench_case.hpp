// SPDX-License-Identifier: MIT
/// \file fluid_bench_case.hpp
/// fluid_bench's case (one home, shared with fluid_memory_probe): a periodic lattice of about
/// n_target particles at dx = 1, h = 3 dx, c_0 = 10, eta = 1, k_B T = 0.01.
#pragma once

#include <cmath>

#include "fluid_test_scenes.hpp"
#include "sadr/fluid/fluid_model.hpp"

namespace sadr::fluid::bench {

inline ParticleState bench_case(int dim, long n_target, FluidModel& m) {
  test::LatticeSpec ls;
  ls.dimension = dim;
  const int side =
      static_cast<int>(std::lround(std::pow(static_cast<double>(n_target), 1.0 / dim)));
  ls.n = {side, dim > 1 ? side : 1, dim > 2 ? side : 1};
  ls.dx = 1.0;
  ParticleState p = test::make_lattice(ls, m.box);
  m.smoothing_length = 3.0;
  m.sound_speed = 10.0;
  m.shear_viscosity = 1.0;
  m.temperature = 0.01;
  m.seed = 1;
  return p;
}

}  // namespace sadr::fluid::bench
