// SPDX-License-Identifier: MIT
/// \file kernel.hpp
/// Wendland C2 kernel with support radius h, the formula of
/// fluid_service/core/include/sadr/fluid/kernel.hpp copied (geometry does not link fluid_core):
/// W = alpha_D (1 + 4q)(1 - q)^4, F = -(1/r) dW/dr = 20 alpha_D (1 - q)^3 / h^2, q = r / h,
/// alpha_D = 7 / (pi h^2) (2D), 21 / (2 pi h^3) (3D).
#pragma once

#include <numbers>

namespace sadr::geometry {

class WendlandC2 {
 public:
  WendlandC2(int dimension, double h) : inv_h_(1.0 / h) {
    const double pi = std::numbers::pi;
    alpha_ = dimension == 2 ? 7.0 / (pi * h * h) : 21.0 / (2.0 * pi * h * h * h);
    f_coef_ = 20.0 * alpha_ * inv_h_ * inv_h_;
  }
  [[nodiscard]] double w(double r) const {
    const double q = r * inv_h_;
    if (q >= 1.0) return 0.0;
    const double s = 1.0 - q;
    return alpha_ * (1.0 + 4.0 * q) * s * s * s * s;
  }
  /// F(r) = -(1/r) dW/dr >= 0.
  [[nodiscard]] double f(double r) const {
    const double q = r * inv_h_;
    if (q >= 1.0) return 0.0;
    const double s = 1.0 - q;
    return f_coef_ * s * s * s;
  }

 private:
  double inv_h_, alpha_ = 0, f_coef_ = 0;
};

}  // namespace sadr::geometry
