// SPDX-License-Identifier: MIT
#include "sadr/ssa/neighbor_list.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace sadr::ssa {

namespace {

/// Coordinates of the active axes, wrapped into [lo, hi) on periodic axes.
std::vector<double> wrapped_coordinates(const Box& box, std::span<const double> positions) {
  const int d = box.dimension;
  const std::size_t n = positions.size() / 3;
  std::vector<double> x(static_cast<std::size_t>(d) * n);
  for (std::size_t i = 0; i < n; ++i) {
    for (int a = 0; a < d; ++a) {
      double v = positions[3 * i + a];
      if (box.periodic[a]) {
        const double len = box.length(a);
        v = box.lo[a] + (v - box.lo[a]) - len * std::floor((v - box.lo[a]) / len);
        if (v >= box.hi[a]) v = box.lo[a];  // round-off at the upper edge
      }
      x[d * i + a] = v;
    }
  }
  return x;
}

/// Minimum image of a coordinate difference on a periodic axis of length len.
inline double wrap(double dx, double len) {
  if (dx > 0.5 * len) return dx - len;
  if (dx < -0.5 * len) return dx + len;
  return dx;
}

/// Squared minimum-image distance between wrapped points p and q.
inline double distance2(const Box& box, int d, const double* p, const double* q) {
  double r2 = 0;
  for (int a = 0; a < d; ++a) {
    double dx = p[a] - q[a];
    if (box.periodic[a]) {
      const double len = box.hi[a] - box.lo[a];
      if (dx > 0.5 * len) {
        dx -= len;
      } else if (dx < -0.5 * len) {
        dx += len;
      }
    }
    r2 += dx * dx;
  }
  return r2;
}

}  // namespace

NeighborList build_neighbor_list(const Box& box, std::span<const double> positions, double cutoff) {
  const int d = box.dimension;
  const std::size_t n = positions.size() / 3;
  const std::vector<double> x = wrapped_coordinates(box, positions);
  std::array<int, 3> nc{1, 1, 1};
  std::array<double, 3> inv_w{0, 0, 0};
  for (int a = 0; a < d; ++a) {
    // Cells at least `cutoff` wide, so neighbours are in the 3^d surrounding cells.
    // Capped at ~2 N^(1/d) per axis so a tiny cutoff in a large box cannot
    // allocate far more cells than particles (wider cells stay correct).
    const double cells = std::floor(box.length(a) / cutoff);
    const double cap = 2.0 * std::ceil(std::pow(static_cast<double>(n) + 1.0, 1.0 / d)) + 2.0;
    nc[a] = static_cast<int>(std::clamp(cells, 1.0, cap));
    inv_w[a] = nc[a] / box.length(a);
  }
  const std::size_t ncell = static_cast<std::size_t>(nc[0]) * nc[1] * nc[2];
  std::vector<std::uint32_t> cell_of(n);
  std::vector<std::uint32_t> cell_start(ncell + 1, 0);
  auto coord = [&](std::size_t i, int a) {
    const int c = static_cast<int>((x[d * i + a] - box.lo[a]) * inv_w[a]);
    return std::clamp(c, 0, nc[a] - 1);
  };
  for (std::size_t i = 0; i < n; ++i) {
    int c[3] = {0, 0, 0};
    for (int a = 0; a < d; ++a) c[a] = coord(i, a);
    cell_of[i] = static_cast<std::uint32_t>((c[2] * nc[1] + c[1]) * nc[0] + c[0]);
    ++cell_start[cell_of[i] + 1];
  }
  for (std::size_t c = 0; c < ncell; ++c) cell_start[c + 1] += cell_start[c];
  std::vector<std::uint32_t> members(n);
  {
    std::vector<std::uint32_t> fill(cell_start.begin(), cell_start.end() - 1);
    for (std::size_t i = 0; i < n; ++i) members[fill[cell_of[i]]++] = static_cast<std::uint32_t>(i);
  }

  // Coordinates in cell order (3 per particle, unused axes 0): the inner loop
  // streams contiguous memory.
  std::vector<double> xs(3 * n, 0.0);
  for (std::size_t m = 0; m < n; ++m) {
    for (int a = 0; a < d; ++a) xs[3 * m + a] = x[d * members[m] + a];
  }
  // Periodic axes with >= 3 cells: a wrapped neighbour cell is reached with a
  // known image shift of -L or +L, so no per-pair minimum image is needed.
  // Periodic axes with < 3 cells may reach one cell with two shifts: there the
  // pair distance takes the minimum image explicitly.
  std::array<bool, 3> min_image{false, false, false};
  for (int a = 0; a < d; ++a) min_image[a] = box.periodic[a] && nc[a] < 3;

  NeighborList out;
  out.row_start.resize(n + 1);
  out.col.reserve(n * (d == 1 ? 4 : d == 2 ? 16 : 40));
  out.r2.reserve(out.col.capacity());
  const double cut2 = cutoff * cutoff;
  for (std::size_t i = 0; i < n; ++i) {
    out.row_start[i] = static_cast<std::uint32_t>(out.col.size());
    std::array<std::array<int, 3>, 3> cand{};
    std::array<std::array<double, 3>, 3> shift{};
    std::array<int, 3> ncand{1, 1, 1};
    std::array<double, 3> xi{0, 0, 0};
    for (int a = 0; a < d; ++a) {
      xi[a] = x[d * i + a];
      const int c = coord(i, a);
      const double len = box.length(a);
      int k = 0;
      for (int off = -1; off <= 1; ++off) {
        int cc = c + off;
        double sh = 0;
        if (box.periodic[a]) {
          if (cc < 0) cc += nc[a], sh = -len;
          if (cc >= nc[a]) cc -= nc[a], sh = len;
        } else if (cc < 0 || cc >= nc[a]) {
          continue;
        }
        if (min_image[a]) {
          sh = 0;
          bool dup = false;
          for (int m = 0; m < k; ++m) dup = dup || cand[a][m] == cc;
          if (dup) continue;
        }
        cand[a][k] = cc;
        shift[a][k] = sh;
        ++k;
      }
      ncand[a] = k;
    }
    for (int iz = 0; iz < ncand[2]; ++iz) {
      for (int iy = 0; iy < ncand[1]; ++iy) {
        for (int ix = 0; ix < ncand[0]; ++ix) {
          const std::size_t c =
              (static_cast<std::size_t>(cand[2][iz]) * nc[1] + cand[1][iy]) * nc[0] + cand[0][ix];
          const double sx = shift[0][ix], sy = shift[1][iy], sz = shift[2][iz];
          for (std::uint32_t m = cell_start[c]; m < cell_start[c + 1]; ++m) {
            // (x_i - x_j) - shift, in this order, so that r_ij and r_ji round
            // identically (symmetric D_ij stays exactly symmetric).
            double dx = (xi[0] - xs[3 * m]) - sx, dy = (xi[1] - xs[3 * m + 1]) - sy,
                   dz = (xi[2] - xs[3 * m + 2]) - sz;
            if (min_image[0]) dx = wrap(dx, box.length(0));
            if (min_image[1]) dy = wrap(dy, box.length(1));
            if (min_image[2]) dz = wrap(dz, box.length(2));
            const double r2 = dx * dx + dy * dy + dz * dz;
            if (r2 < cut2 && members[m] != i) {
              out.col.push_back(members[m]);
              out.r2.push_back(r2);
            }
          }
        }
      }
    }
  }
  out.row_start[n] = static_cast<std::uint32_t>(out.col.size());
  return out;
}

NeighborList brute_force_neighbor_list(const Box& box, std::span<const double> positions,
                                       double cutoff) {
  const int d = box.dimension;
  const std::size_t n = positions.size() / 3;
  const std::vector<double> x = wrapped_coordinates(box, positions);
  NeighborList out;
  out.row_start.resize(n + 1);
  for (std::size_t i = 0; i < n; ++i) {
    out.row_start[i] = static_cast<std::uint32_t>(out.col.size());
    for (std::size_t j = 0; j < n; ++j) {
      if (j == i) continue;
      const double r2 = distance2(box, d, &x[d * i], &x[d * j]);
      if (r2 < cutoff * cutoff) {
        out.col.push_back(static_cast<std::uint32_t>(j));
        out.r2.push_back(r2);
      }
    }
  }
  out.row_start[n] = static_cast<std::uint32_t>(out.col.size());
  return out;
}

}  // namespace sadr::ssa
