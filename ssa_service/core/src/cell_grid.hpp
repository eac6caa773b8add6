// SPDX-License-Identifier: MIT
/// \file cell_grid.hpp
/// Cell lists shared by build_neighbor_list(), the full-stencil graph path and
/// GraphBuilder's row search: the particles binned into cells at least `cutoff`
/// wide, their coordinates copied in cell order (the inner loops stream contiguous
/// memory), and a visitor over the neighbours of one particle. Allocations are
/// kept between builds.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "sadr/common/particle_state.hpp"
#include "sadr/common/periodic.hpp"

namespace sadr::ssa::detail {

class CellGrid {
 public:
  /// Bins the particles (3 coordinates each, axes >= box.dimension ignored).
  void build(const Box& box, std::span<const double> positions, double cutoff);

  /// Calls f(j, r2) for every j != i with |x_i - x_j|^2 = r2 < cutoff^2, in cell
  /// order (cells z-major, then members in index order). D = box.dimension.
  template <int D, typename F>
  void for_each_neighbor(std::uint32_t i, F&& f) const {
    std::array<std::array<int, 3>, 3> cand{};
    std::array<std::array<double, 3>, 3> shift{};
    std::array<int, 3> ncand{1, 1, 1};
    std::array<double, 3> xi{0, 0, 0};
    for (int a = 0; a < D; ++a) {
      xi[a] = x_[D * i + a];
      const int c = coord(xi[a], a);
      int k = 0;
      for (int off = -1; off <= 1; ++off) {
        int cc = c + off;
        double sh = 0;
        if (periodic_[a]) {
          if (cc < 0) cc += nc_[a], sh = -len_[a];
          if (cc >= nc_[a]) cc -= nc_[a], sh = len_[a];
        } else if (cc < 0 || cc >= nc_[a]) {
          continue;
        }
        if (min_image_[a]) {
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
    if (any_min_image_) {
      scan<D, true>(i, xi, cand, shift, ncand, f);
    } else {
      scan<D, false>(i, xi, cand, shift, ncand, f);
    }
  }

  /// True if every neighbour cell is reached through exactly one periodic image
  /// (no periodic axis with < 3 cells), so a pair distance needs no per-pair
  /// minimum image: what the row search through view() assumes.
  [[nodiscard]] bool single_image() const { return !any_min_image_; }

  [[nodiscard]] int dimension() const { return d_; }

  /// Read-only view of the grid for the vectorised row search (graph_search.cpp).
  struct View {
    int d;
    std::array<int, 3> nc;
    std::array<bool, 3> periodic;
    std::array<double, 3> len;
    double cut2;
    const double* x;   ///< wrapped coordinates, d per particle, index order
    const double* xs;  ///< the same in cell order
    const std::uint32_t* members;
    const std::uint32_t* cell_start;
  };
  [[nodiscard]] View view() const {
    return View{d_,
                nc_,
                periodic_,
                len_,
                cut2_,
                x_.data(),
                xs_.data(),
                members_.data(),
                cell_start_.data()};
  }
  /// Cell coordinate of position x on axis a (clamped into the grid).
  [[nodiscard]] int coord(double x, int a) const {
    const int c = static_cast<int>((x - lo_[a]) * inv_w_[a]);
    return c < 0 ? 0 : (c > nc_[a] - 1 ? nc_[a] - 1 : c);
  }

 private:
  template <int D, bool kMinImage, typename F>
  void scan(std::uint32_t i, const std::array<double, 3>& xi,
            const std::array<std::array<int, 3>, 3>& cand,
            const std::array<std::array<double, 3>, 3>& shift, const std::array<int, 3>& ncand,
            F& f) const {
    // Locals: the callback writes memory, so members would be reloaded per pair.
    const double* xs = xs_.data();
    const std::uint32_t* members = members_.data();
    const std::uint32_t* cell_start = cell_start_.data();
    const double cut2 = cut2_;
    const double x0 = xi[0];
    [[maybe_unused]] const double x1 = xi[1], x2 = xi[2];
    const std::array<bool, 3> mi = min_image_;
    const std::array<double, 3> len = len_;
    const std::size_t nc0 = static_cast<std::size_t>(nc_[0]),
                      nc1 = static_cast<std::size_t>(nc_[1]);
    for (int iz = 0; iz < ncand[2]; ++iz) {
      for (int iy = 0; iy < ncand[1]; ++iy) {
        const std::size_t row = (static_cast<std::size_t>(cand[2][iz]) * nc1 + cand[1][iy]) * nc0;
        for (int ix = 0; ix < ncand[0]; ++ix) {
          const std::size_t c = row + static_cast<std::size_t>(cand[0][ix]);
          const double sx = shift[0][ix];
          [[maybe_unused]] const double sy = shift[1][iy], sz = shift[2][iz];
          const std::uint32_t end = cell_start[c + 1];
          for (std::uint32_t m = cell_start[c]; m < end; ++m) {
            // (x_i - x_j) - shift, in this order, so that r_ij and r_ji round
            // identically (symmetric D_ij stays exactly symmetric).
            double dx = (x0 - xs[D * m]) - sx;
            if (kMinImage && mi[0]) dx = minimum_image(dx, len[0]);
            double r2 = dx * dx;
            if constexpr (D >= 2) {
              double dy = (x1 - xs[D * m + 1]) - sy;
              if (kMinImage && mi[1]) dy = minimum_image(dy, len[1]);
              r2 += dy * dy;
            }
            if constexpr (D >= 3) {
              double dz = (x2 - xs[D * m + 2]) - sz;
              if (kMinImage && mi[2]) dz = minimum_image(dz, len[2]);
              r2 += dz * dz;
            }
            if (r2 < cut2 && members[m] != i) f(members[m], r2);
          }
        }
      }
    }
  }

  int d_ = 3;
  std::array<int, 3> nc_{1, 1, 1};
  std::array<double, 3> inv_w_{0, 0, 0}, lo_{0, 0, 0}, len_{0, 0, 0};
  std::array<bool, 3> periodic_{false, false, false}, min_image_{false, false, false};
  bool any_min_image_ = false;
  double cut2_ = 0;
  std::vector<double> x_;   ///< wrapped coordinates, D per particle, index order
  std::vector<double> xs_;  ///< the same in cell order
  std::vector<std::uint32_t> cell_of_, cell_start_, members_, fill_;
};

}  // namespace sadr::ssa::detail
