// SPDX-License-Identifier: MIT
/// \file sweep_test_support.hpp
/// Scenes shared by the sweep and override end-to-end tests.
#pragma once

#include <sstream>
#include <string>

namespace sadr::e2e {

/// Immigration-death on a periodic 1D static lattice of `particles` voxels
/// without diffusion: every voxel is an independent birth-death process
/// 0 -> A (k V per voxel, V = 1/particles), A -> 0 (g), X(0) = 0, so
/// X_i(t) ~ Poisson(k V / g (1 - exp(-g t))) exactly.
inline std::string birth_death_scene(int particles, double k, double g, double end,
                                     const std::string& times, const std::string& formats) {
  std::ostringstream s;
  s << "name: birth_death\n"
       "dimension: 1\n"
       "box: {lower: [0.0], upper: [1.0], periodic: [true]}\n"
       "particles: {spacing: "
    << 1.0 / particles
    << ", density: 1.0}\n"
       "fluid: {backend: static, h_over_dx: 1.5}\n"
       "species: [{name: A, diffusivity: 0.0}]\n"
       "reactions:\n"
       "  - {name: birth, equation: \"0 -> A\", rate: "
    << k
    << "}\n"
       "  - {name: death, equation: \"A -> 0\", rate: "
    << g << "}\n"
    << "time: {coupling_step: " << end / 4 << ", end: " << end << "}\n"
    << "output: {times: " << times << ", formats: " << formats << "}\n"
    << "seed: 5\n";
  return s.str();
}

}  // namespace sadr::e2e
