// SPDX-License-Identifier: MIT
/// \file periodic_box.hpp
/// Minimum-image displacements and position wrapping for a sadr::Box.
#pragma once

#include <array>
#include <limits>

#include "sadr/common/particle_state.hpp"
#include "sadr/common/periodic.hpp"

namespace sadr::fluid {

/// Precomputed box geometry. Positions are kept inside [lo, hi) on periodic axes.
class PeriodicBox {
 public:
  PeriodicBox() = default;
  explicit PeriodicBox(const Box& box) : box_(box) {
    for (int a = 0; a < 3; ++a) {
      len_[a] = box.hi[a] - box.lo[a];
      half_[a] = 0.5 * len_[a];
      per_[a] = a < box.dimension && box.periodic[a];
      walled_[a] = a < box.dimension && !box.periodic[a];
      half_or_inf_[a] = per_[a] ? half_[a] : std::numeric_limits<double>::infinity();
    }
  }
  /// minimum_image() on the first D axes only, branch-free (same result: the shift is applied
  /// iff |d_a| > L_a/2 on a periodic axis); for the SDPD pair gather.
  template <int D>
  void minimum_image_first(double* d) const {
    for (int a = 0; a < D; ++a) {
      double t = d[a];
      t = t > half_or_inf_[a] ? t - len_[a] : t;
      t = t < -half_or_inf_[a] ? t + len_[a] : t;
      d[a] = t;
    }
  }
  /// d = the minimum image of x_i - x_j on the first D axes; returns |d|^2 (the common first
  /// step of every pair gather).
  template <int D>
  double offset_first(const double* xi, const double* xj, double* d) const {
    for (int a = 0; a < D; ++a) d[a] = xi[a] - xj[a];
    minimum_image_first<D>(d);
    double r2 = 0;
    for (int a = 0; a < D; ++a) r2 += d[a] * d[a];
    return r2;
  }
  /// Replaces d (= x_i - x_j) by its minimum image on periodic axes (|d_a| <= L_a/2).
  /// The rule is sadr::minimum_image (common/periodic.hpp), the SSA's too.
  void minimum_image(double* d) const {
    for (int a = 0; a < 3; ++a) {
      if (per_[a]) d[a] = sadr::minimum_image(d[a], len_[a]);
    }
  }
  /// Wraps a position into [lo, hi) on periodic axes (one period at most per call is enough
  /// for sub-step displacements; larger jumps are caught by the blow-up check).
  void wrap(double* x) const {
    for (int a = 0; a < 3; ++a) {
      if (!per_[a]) continue;
      if (x[a] >= box_.hi[a]) {
        x[a] -= len_[a];
      } else if (x[a] < box_.lo[a]) {
        x[a] += len_[a];
      }
    }
  }
  /// True if x lies inside the box on every active walled axis.
  [[nodiscard]] bool inside(const double* x) const {
    for (int a = 0; a < 3; ++a) {
      if (walled_[a] && (x[a] < box_.lo[a] || x[a] > box_.hi[a])) return false;
    }
    return true;
  }
  [[nodiscard]] const Box& box() const { return box_; }
  [[nodiscard]] bool periodic(int axis) const { return per_[axis]; }
  [[nodiscard]] double length(int axis) const { return len_[axis]; }

 private:
  Box box_{};
  std::array<double, 3> len_{1, 1, 1}, half_{0.5, 0.5, 0.5};
  std::array<double, 3> half_or_inf_{0.5, 0.5, 0.5};  ///< L/2 on periodic axes, else +inf
  std::array<bool, 3> per_{false, false, false};
  std::array<bool, 3> walled_{false, false, false};
};

}  // namespace sadr::fluid
