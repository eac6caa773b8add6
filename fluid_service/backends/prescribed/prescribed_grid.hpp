// SPDX-License-Identifier: MIT
/// \file prescribed_grid.hpp
/// The `csv` field of the "prescribed" backend: a steady velocity field sampled on a rectilinear
/// grid (every combination of the distinct x, y, z values, any spacing) read from a CSV file, and
/// interpolated multilinearly between the grid points (linear in 1D, bilinear in 2D, trilinear in
/// 3D). The interpolant is continuous, exact for a field linear in each coordinate, and its error
/// is second order in the spacing: |u_h - u| <= h^2/8 max|d^2u/dx_a^2| summed over the axes.
///
/// File: a header row naming the columns, then one row per grid point; the columns are the
/// active axes' coordinates and velocity components, in any order: `x, ux` (1D), `x, y, ux, uy`
/// (2D), `x, y, z, ux, uy, uz` (3D) [length, length/time]. Blank lines and lines starting with
/// `#` are skipped. Coordinates that differ by less than 1e-9 of their axis' extent are one grid
/// value. Refused, with file:line, column and value: a missing, repeated or unknown column, a row
/// of the wrong length, a value that is not a finite number, a point given twice, a grid point
/// missing (named), an axis with fewer than 2 values, and on a periodic axis a grid that does
/// not span the box (the position is wrapped into the box before the look-up).
/// On a walled axis the velocity is known only inside the grid: a position outside it is
/// refused (GridField::velocity returns false; the backend names the particle).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "sadr/common/particle_state.hpp"

namespace sadr::fluid {

class GridField {
 public:
  GridField() = default;
  /// Reads `path` for `box` (its dimension and periodic axes); InvalidArgument as above.
  static GridField read(const std::string& path, const Box& box);
  /// v = the interpolated velocity at x (components beyond the dimension 0); false, v untouched,
  /// when x lies outside the grid along a walled axis.
  bool velocity(const double* x, double* v) const;
  /// The grid's extent along axis a [length].
  [[nodiscard]] double lo(int a) const { return axes_[a].front(); }
  [[nodiscard]] double hi(int a) const { return axes_[a].back(); }
  [[nodiscard]] std::size_t points(int a) const { return axes_[a].size(); }
  [[nodiscard]] const std::string& path() const { return path_; }
  [[nodiscard]] int dimension() const { return dim_; }
  /// "(x, y)" of a position, for messages (10 digits).
  [[nodiscard]] std::string point(const double* x) const;
  /// "[x0, x1] x [y0, y1]", for messages.
  [[nodiscard]] std::string extent() const;

 private:
  int dim_ = 0;
  std::string path_;
  std::array<std::vector<double>, 3> axes_{};  ///< sorted grid values of each active axis
  std::array<bool, 3> periodic_{};
  std::array<double, 3> box_lo_{}, box_len_{};
  std::array<std::size_t, 3> stride_{};  ///< node index = sum_a i_a stride_a
  std::vector<double> u_;                ///< dim components per node
};

}  // namespace sadr::fluid
