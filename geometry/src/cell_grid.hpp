// SPDX-License-Identifier: MIT
// Uniform cell list over a box, periodic per axis by minimum image (private header).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "sadr/common/status.hpp"
#include "sadr/geometry/vec.hpp"

namespace sadr::geometry {

class CellGrid {
 public:
  CellGrid(const Aabb& box, int dim, std::array<bool, 3> periodic, double reach)
      : box_(box), dim_(dim), periodic_(periodic) {
    for (int a = 0; a < 3; ++a) {
      len_[a] = box.extent()[a];
      n_[a] = a < dim ? std::max(1, static_cast<int>(std::floor(len_[a] / reach))) : 1;
      if (a < dim && periodic[a] && n_[a] < 3) {
        throw InvalidArgument("a periodic axis must be at least 3 kernel supports long; axis " +
                              std::to_string(a) + " is " + format_value(len_[a]) +
                              " for a support of " + format_value(reach));
      }
      if (a >= dim) periodic_[a] = false;
      cell_[a] = a < dim ? len_[a] / n_[a] : 1.0;
    }
  }

  void build(const std::vector<Vec3>& x) {
    start_.assign(static_cast<std::size_t>(n_[0]) * n_[1] * n_[2] + 1, 0);
    cell_of_.resize(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
      cell_of_[i] = flat(coords(x[i]));
      ++start_[cell_of_[i] + 1];
    }
    for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    items_.resize(x.size());
    std::vector<int> fill(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < x.size(); ++i) items_[fill[cell_of_[i]]++] = static_cast<int>(i);
  }

  /// Calls f(j, xi - xj) (minimum image on periodic axes) for every j in the 3^d cells around xi.
  template <class F>
  void for_neighbors(Vec3 xi, const std::vector<Vec3>& x, F&& f) const {
    const auto c = coords(xi);
    const int zr = dim_ == 3 ? 1 : 0;
    for (int dz = -zr; dz <= zr; ++dz) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          std::array<int, 3> cc{c[0] + dx, c[1] + dy, c[2] + dz};
          bool ok = true;
          for (int a = 0; a < 3; ++a) {
            if (cc[a] < 0 || cc[a] >= n_[a]) {
              if (!periodic_[a]) ok = false;
              cc[a] = (cc[a] + n_[a]) % n_[a];
            }
          }
          if (!ok) continue;
          const int fc = flat(cc);
          for (int k = start_[fc]; k < start_[fc + 1]; ++k) {
            const int j = items_[k];
            f(j, min_image(xi - x[j]));
          }
        }
      }
    }
  }

  [[nodiscard]] Vec3 min_image(Vec3 d) const {
    // Positions lie in the box, so one period at most.
    for (int a = 0; a < 3; ++a) {
      if (!periodic_[a]) continue;
      if (d[a] > 0.5 * len_[a]) {
        d[a] -= len_[a];
      } else if (d[a] < -0.5 * len_[a]) {
        d[a] += len_[a];
      }
    }
    return d;
  }
  /// Wraps periodic axes into the box and clamps the others.
  [[nodiscard]] Vec3 confine(Vec3 p) const {
    for (int a = 0; a < dim_; ++a) {
      if (periodic_[a]) {
        p[a] =
            box_.lo[a] + (p[a] - box_.lo[a]) - len_[a] * std::floor((p[a] - box_.lo[a]) / len_[a]);
      } else {
        p[a] = std::clamp(p[a], box_.lo[a], box_.hi[a]);
      }
    }
    return p;
  }

 private:
  std::array<int, 3> coords(Vec3 p) const {
    std::array<int, 3> c{};
    for (int a = 0; a < dim_; ++a) {
      c[a] = std::clamp(static_cast<int>(std::floor((p[a] - box_.lo[a]) / cell_[a])), 0, n_[a] - 1);
    }
    return c;
  }
  int flat(std::array<int, 3> c) const { return (c[2] * n_[1] + c[1]) * n_[0] + c[0]; }
  Aabb box_;
  int dim_;
  std::array<bool, 3> periodic_;
  std::array<int, 3> n_{};
  std::array<double, 3> len_{}, cell_{};
  std::vector<int> start_, cell_of_, items_;
};

}  // namespace sadr::geometry
