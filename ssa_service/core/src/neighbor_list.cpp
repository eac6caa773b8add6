// SPDX-License-Identifier: MIT
#include "sadr/ssa/neighbor_list.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "cell_grid.hpp"
#include "sadr/common/periodic.hpp"

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
      if (box.periodic[a]) v = wrap_into(v, box.lo[a], box.hi[a]);
      x[d * i + a] = v;
    }
  }
  return x;
}

/// Squared minimum-image distance between wrapped points p and q.
inline double distance2(const Box& box, int d, const double* p, const double* q) {
  double r2 = 0;
  for (int a = 0; a < d; ++a) {
    double dx = p[a] - q[a];
    if (box.periodic[a]) dx = minimum_image(dx, box.hi[a] - box.lo[a]);
    r2 += dx * dx;
  }
  return r2;
}

}  // namespace

namespace detail {

void CellGrid::build(const Box& box, std::span<const double> positions, double cutoff) {
  const int d = box.dimension;
  d_ = d;
  const std::size_t n = positions.size() / 3;
  cut2_ = cutoff * cutoff;
  nc_ = {1, 1, 1};
  inv_w_ = {0, 0, 0};
  any_min_image_ = false;
  for (int a = 0; a < 3; ++a) {
    lo_[a] = box.lo[a];
    len_[a] = box.length(a);
    periodic_[a] = a < d && box.periodic[a];
    min_image_[a] = false;
  }
  for (int a = 0; a < d; ++a) {
    // Cells at least `cutoff` wide, so neighbours are in the 3^d surrounding cells.
    // Capped at ~2 N^(1/d) per axis so a tiny cutoff in a large box cannot
    // allocate far more cells than particles (wider cells stay correct).
    const double cells = std::floor(box.length(a) / cutoff);
    const double cap = 2.0 * std::ceil(std::pow(static_cast<double>(n) + 1.0, 1.0 / d)) + 2.0;
    nc_[a] = static_cast<int>(std::clamp(cells, 1.0, cap));
    inv_w_[a] = nc_[a] / box.length(a);
    // Periodic axes with >= 3 cells: a wrapped neighbour cell is reached with a
    // known image shift of -L or +L, so no per-pair minimum image is needed.
    // Periodic axes with < 3 cells may reach one cell with two shifts: there the
    // pair distance takes the minimum image explicitly.
    min_image_[a] = box.periodic[a] && nc_[a] < 3;
    any_min_image_ = any_min_image_ || min_image_[a];
  }
  // Wrapped coordinates of the active axes.
  x_.resize(static_cast<std::size_t>(d) * n);
  for (std::size_t i = 0; i < n; ++i) {
    for (int a = 0; a < d; ++a) {
      double v = positions[3 * i + a];
      if (box.periodic[a]) v = wrap_into(v, box.lo[a], box.hi[a]);
      x_[d * i + a] = v;
    }
  }
  const std::size_t ncell = static_cast<std::size_t>(nc_[0]) * nc_[1] * nc_[2];
  cell_of_.resize(n);
  cell_start_.assign(ncell + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    int c[3] = {0, 0, 0};
    for (int a = 0; a < d; ++a) c[a] = coord(x_[d * i + a], a);
    cell_of_[i] = static_cast<std::uint32_t>((c[2] * nc_[1] + c[1]) * nc_[0] + c[0]);
    ++cell_start_[cell_of_[i] + 1];
  }
  for (std::size_t c = 0; c < ncell; ++c) cell_start_[c + 1] += cell_start_[c];
  members_.resize(n);
  fill_.assign(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t i = 0; i < n; ++i) {
    members_[fill_[cell_of_[i]]++] = static_cast<std::uint32_t>(i);
  }
  xs_.resize(static_cast<std::size_t>(d) * n);
  for (std::size_t m = 0; m < n; ++m) {
    for (int a = 0; a < d; ++a) xs_[d * m + a] = x_[d * members_[m] + a];
  }
}

}  // namespace detail

namespace {

template <int D>
void collect(const detail::CellGrid& grid, std::size_t n, NeighborList& out) {
  for (std::size_t i = 0; i < n; ++i) {
    out.row_start[i] = static_cast<std::uint32_t>(out.col.size());
    grid.for_each_neighbor<D>(static_cast<std::uint32_t>(i), [&](std::uint32_t j, double r2) {
      out.col.push_back(j);
      out.r2.push_back(r2);
    });
  }
}

}  // namespace

NeighborList build_neighbor_list(const Box& box, std::span<const double> positions, double cutoff) {
  const int d = box.dimension;
  const std::size_t n = positions.size() / 3;
  detail::CellGrid grid;
  grid.build(box, positions, cutoff);
  NeighborList out;
  out.row_start.resize(n + 1);
  out.col.reserve(n * (d == 1 ? 4 : d == 2 ? 16 : 40));
  out.r2.reserve(out.col.capacity());
  if (d == 1) collect<1>(grid, n, out);
  if (d == 2) collect<2>(grid, n, out);
  if (d == 3) collect<3>(grid, n, out);
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
