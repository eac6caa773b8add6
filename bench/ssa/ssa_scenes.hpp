// SPDX-License-Identifier: MIT
/// \file ssa_scenes.hpp
/// The ssa benchmarks' lattices and models (ssa_bench, ssa_memory_probe).
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "sadr/common/particle_state.hpp"
#include "sadr/ssa/diffusion_graph.hpp"
#include "sadr/ssa/model.hpp"

namespace sadr::ssa::bench {

inline ParticleState lattice(int dim, int n, double dx, double jitter, std::uint64_t seed) {
  ParticleState p;
  p.dimension = dim;
  std::size_t count = 1;
  for (int a = 0; a < dim; ++a) count *= static_cast<std::size_t>(n);
  p.resize(count, false);
  std::mt19937_64 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (std::size_t i = 0; i < count; ++i) {
    std::size_t rest = i;
    for (int a = 0; a < dim; ++a) {
      p.positions[3 * i + a] = (static_cast<double>(rest % n) + 0.5 + jitter * u(gen)) * dx;
      rest /= n;
    }
    p.masses[i] = std::pow(dx, dim);
  }
  return p;
}

inline Model lattice_model(int dim, int n, double h, bool reactions) {
  Model m;
  m.box.dimension = dim;
  for (int a = 0; a < 3; ++a) {
    m.box.lo[a] = 0;
    m.box.hi[a] = a < dim ? n : 1.0;
    m.box.periodic[a] = a < dim;
  }
  m.smoothing_length = h;
  // kappa such that each of the 6 lattice edges carries hop rate 1 per molecule.
  const double kappa = 1.0 / (2.0 * lucy_f(1.0, h, dim) / (1.0 + 0.01 * h * h));
  m.species = {{"A", kappa}};
  if (reactions) {
    m.species.push_back({"B", kappa});
    m.species.push_back({"C", 0.5 * kappa});
    m.reactions = {{"bind", {{0, 1}, {1, 1}}, {{2, 1}}, 0.5, {}, {}},
                   {"unbind", {{2, 1}}, {{0, 1}, {1, 1}}, 1.0, {}, {}}};
  }
  return m;
}

inline std::vector<std::int64_t> scatter(std::size_t voxels, std::int64_t molecules,
                                         std::uint64_t seed) {
  std::vector<std::int64_t> x(voxels, 0);
  std::mt19937_64 gen(seed);
  for (std::int64_t k = 0; k < molecules; ++k) ++x[gen() % voxels];
  return x;
}

}  // namespace sadr::ssa::bench
