// SPDX-License-Identifier: MIT
/// \file fluid_test_scenes.hpp
/// Small scene builders shared by the fluid tests and benchmarks (lattices with wall layers).
#pragma once

#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "sadr/common/particle_state.hpp"
#include "sadr/fluid/fluid_model.hpp"

namespace sadr::fluid::test {

/// A lattice of fluid particles at (k + 1/2) dx, k = 0..n[a]-1 on each active axis, with
/// `wall_layers` layers of wall particles beyond each walled axis (box enlarged to hold them).
struct LatticeSpec {
  int dimension = 2;
  std::array<int, 3> n{10, 10, 1};
  double dx = 1.0;
  std::array<bool, 3> periodic{true, true, true};
  int wall_layers = 0;
  double rho0 = 1.0;
};

inline ParticleState make_lattice(const LatticeSpec& s, Box& box) {
  box.dimension = s.dimension;
  std::array<int, 3> lo_k{0, 0, 0}, hi_k{1, 1, 1};
  for (int a = 0; a < 3; ++a) {
    if (a >= s.dimension) {
      box.lo[a] = 0;
      box.hi[a] = 1;
      box.periodic[a] = false;
      continue;
    }
    box.periodic[a] = s.periodic[a];
    const int w = s.periodic[a] ? 0 : s.wall_layers;
    lo_k[a] = -w;
    hi_k[a] = s.n[a] + w;
    box.lo[a] = -w * s.dx;
    box.hi[a] = (s.n[a] + w) * s.dx;
  }
  ParticleState p;
  p.dimension = s.dimension;
  double vol = 1;
  for (int a = 0; a < s.dimension; ++a) vol *= s.dx;
  for (int kz = lo_k[2]; kz < hi_k[2]; ++kz) {
    for (int ky = lo_k[1]; ky < hi_k[1]; ++ky) {
      for (int kx = lo_k[0]; kx < hi_k[0]; ++kx) {
        const std::array<int, 3> k{kx, ky, kz};
        bool wall = false;
        std::array<double, 3> x{0, 0, 0};
        for (int a = 0; a < s.dimension; ++a) {
          x[a] = (k[a] + 0.5) * s.dx;
          wall = wall || k[a] < 0 || k[a] >= s.n[a];
        }
        p.positions.insert(p.positions.end(), x.begin(), x.end());
        p.kinds.push_back(wall ? ParticleKind::kWall : ParticleKind::kFluid);
        p.masses.push_back(s.rho0 * vol);
        p.densities.push_back(s.rho0);
      }
    }
  }
  const std::size_t n = p.densities.size();
  p.velocities.assign(3 * n, 0.0);
  p.ids.resize(n);
  for (std::size_t i = 0; i < n; ++i) p.ids[i] = i;
  return p;
}

/// Directory of the reference CSVs (SADR_REFS from ctest, else the source tree copy).
inline std::string refs_dir() {
  if (const char* e = std::getenv("SADR_REFS")) return e;
  return std::string(SADR_SOURCE_DIR) + "/tests/data/refs";
}

/// Reads a refs CSV ('#' comment lines, one header row) into columns by name.
inline std::map<std::string, std::vector<double>> read_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::string line;
  std::vector<std::string> names;
  std::map<std::string, std::vector<double>> cols;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::stringstream ss(line);
    std::string cell;
    if (names.empty()) {
      while (std::getline(ss, cell, ',')) names.push_back(cell);
      continue;
    }
    std::size_t k = 0;
    while (std::getline(ss, cell, ',') && k < names.size()) {
      cols[names[k++]].push_back(cell == "inf" ? INFINITY : cell == "nan" ? NAN : std::stod(cell));
    }
  }
  return cols;
}

}  // namespace sadr::fluid::test
