// SPDX-License-Identifier: MIT
/// \file line_scenes.hpp
/// 1-D particle lines for the frozen-particle diffusion validations (cases 1-3 of
/// reference_solutions.hpp, A + B -> 0 against tests/data/refs/annihilation_1d_subset.csv).
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "sadr/common/particle_state.hpp"
#include "sadr/fluid/fluid_model.hpp"

namespace sadr::fluid::test {

/// Particles at the given positions (fluid first, then walls), unit density, mass = dx.
inline ParticleState make_line(const std::vector<double>& fluid, const std::vector<double>& walls,
                               double dx) {
  ParticleState p;
  p.dimension = 1;
  for (double x : fluid) {
    p.positions.insert(p.positions.end(), {x, 0.0, 0.0});
    p.kinds.push_back(ParticleKind::kFluid);
  }
  for (double x : walls) {
    p.positions.insert(p.positions.end(), {x, 0.0, 0.0});
    p.kinds.push_back(ParticleKind::kWall);
  }
  const std::size_t n = p.kinds.size();
  p.masses.assign(n, dx);
  p.densities.assign(n, 1.0);
  p.velocities.assign(3 * n, 0.0);
  p.ids.resize(n);
  for (std::size_t i = 0; i < n; ++i) p.ids[i] = i;
  return p;
}

inline Box line_box(double lo, double hi) {
  Box b;
  b.dimension = 1;
  b.lo = {lo, 0, 0};
  b.hi = {hi, 1, 1};
  b.periodic = {false, false, false};
  return b;
}

/// Prints one machine-readable result line (collected into docs/fluid-core.md).
inline void report(const std::string& text) {
  std::printf("RESULT %s\n", text.c_str());
}

}  // namespace sadr::fluid::test
