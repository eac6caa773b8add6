// SPDX-License-Identifier: MIT
// Lattices as a rectangular cell repeated over the box with a basis of sites (private header).
#pragma once

#include <cmath>
#include <vector>

#include "sadr/geometry/particles.hpp"

namespace sadr::geometry {

struct LatticeCells {
  Vec3 cell;                ///< cell edge lengths
  std::vector<Vec3> basis;  ///< site offsets in the cell [length]
  std::array<long, 3> n{};  ///< cells per axis
  Vec3 origin;              ///< lower corner of cell (0, 0, 0)

  [[nodiscard]] Vec3 site(long i, long j, long k, std::size_t b) const {
    return origin + Vec3{i * cell.x, j * cell.y, k * cell.z} + basis[b];
  }
};

/// One site per spacing^d of volume (particles.hpp, Lattice).
inline LatticeCells make_lattice(int dim, Lattice lattice, double dx, const Aabb& box,
                                 Vec3 offset) {
  LatticeCells l;
  if (lattice == Lattice::kCubic) {
    l.cell = {dx, dx, dim == 3 ? dx : 1.0};
    l.basis = {{0.5 * dx, 0.5 * dx, dim == 3 ? 0.5 * dx : 0.0}};
  } else if (dim == 2) {
    const double b = dx * std::sqrt(2.0 / std::sqrt(3.0));
    const double ry = b * std::sqrt(3.0) / 2.0;
    l.cell = {b, 2 * ry, 1.0};
    l.basis = {{0.25 * b, 0.5 * ry, 0}, {0.75 * b, 1.5 * ry, 0}};
  } else {
    const double a = std::cbrt(4.0) * dx;
    l.cell = {a, a, a};
    l.basis = {{0.25 * a, 0.25 * a, 0.25 * a},
               {0.75 * a, 0.75 * a, 0.25 * a},
               {0.75 * a, 0.25 * a, 0.75 * a},
               {0.25 * a, 0.75 * a, 0.75 * a}};
  }
  const Vec3 ext = box.extent();
  for (int a = 0; a < dim; ++a) {
    l.n[a] = std::max(1L, static_cast<long>(std::floor(ext[a] / l.cell[a] + 1e-9)));
  }
  l.n[2] = dim == 3 ? l.n[2] : 1;
  l.origin = box.lo + dx * offset;
  if (dim == 2) l.origin.z = 0;
  return l;
}

}  // namespace sadr::geometry
