// SPDX-License-Identifier: MIT
/// \file kernel.hpp
/// Smoothing kernels with compact support radius h (docs/method.md section 2).
///
/// Notation: q = r / h with h the SUPPORT radius (W = 0 for r >= h), and
/// F(r) = -(1/r) dW/dr >= 0, finite at r = 0 for both kernels here.
///  - Lucy (1977):   W = alpha_D (1 + 3q)(1 - q)^3,  F = 12 alpha_D (1 - q)^2 / h^2,
///                   alpha_D = 5/(4h), 5/(pi h^2), 105/(16 pi h^3) in 1D/2D/3D.
///  - Wendland C2 (Wendland 1995; Dehnen & Aly 2012): in 2D/3D
///                   W = alpha_D (1 + 4q)(1 - q)^4,  F = 20 alpha_D (1 - q)^3 / h^2,
///                   alpha_D = 7/(pi h^2), 21/(2 pi h^3); in 1D the C2 Wendland
///                   function is (1 + 3q)(1 - q)^3, i.e. identical to Lucy.
#pragma once

#include <cmath>

#include <numbers>
#include <string_view>

namespace sadr::fluid {

enum class KernelType { kLucy, kWendlandC2 };

/// Parses "lucy" or "wendland_c2"; throws InvalidArgument listing the known names.
KernelType parse_kernel(std::string_view name);

/// A radial kernel of dimension 1-3 with support radius h [length].
class Kernel {
 public:
  Kernel() = default;
  /// @param type kernel family; @param dimension 1, 2 or 3; @param h support radius [length].
  Kernel(KernelType type, int dimension, double h) : h_(h), inv_h_(1.0 / h), dim_(dimension) {
    type_ = (dimension == 1) ? KernelType::kLucy : type;  // C2 Wendland == Lucy in 1D
    const double pi = std::numbers::pi;
    double hd = h;
    for (int d = 1; d < dimension; ++d) hd *= h;
    if (type_ == KernelType::kLucy) {
      alpha_ = (dimension == 1 ? 5.0 / 4.0 : dimension == 2 ? 5.0 / pi : 105.0 / (16.0 * pi)) / hd;
      f_coef_ = 12.0 * alpha_ * inv_h_ * inv_h_;
    } else {
      alpha_ = (dimension == 2 ? 7.0 / pi : 21.0 / (2.0 * pi)) / hd;
      f_coef_ = 20.0 * alpha_ * inv_h_ * inv_h_;
    }
    sqrt_f_coef_ = std::sqrt(f_coef_);
  }

  /// W(r) [1/length^d].
  [[nodiscard]] double w(double r) const {
    const double q = r * inv_h_;
    if (q >= 1.0) return 0.0;
    const double s = 1.0 - q;
    if (type_ == KernelType::kLucy) return alpha_ * (1.0 + 3.0 * q) * s * s * s;
    return alpha_ * (1.0 + 4.0 * q) * s * s * s * s;
  }
  /// F(r) = -(1/r) dW/dr >= 0 [1/length^(d+2)], 0 outside the support.
  [[nodiscard]] double f(double r) const {
    const double q = r * inv_h_;
    if (q >= 1.0) return 0.0;
    const double s = 1.0 - q;
    return type_ == KernelType::kLucy ? f_coef_ * s * s : f_coef_ * s * s * s;
  }
  /// sqrt(F(r)) without a square root for Lucy (sqrt(c) (1 - q)); for the noise amplitude.
  [[nodiscard]] double sqrt_f(double r) const {
    const double q = r * inv_h_;
    if (q >= 1.0) return 0.0;
    const double s = 1.0 - q;
    return type_ == KernelType::kLucy ? sqrt_f_coef_ * s : sqrt_f_coef_ * s * std::sqrt(s);
  }
  /// dW/dr [1/length^(d+1)] (<= 0).
  [[nodiscard]] double dw_dr(double r) const { return -r * f(r); }

  [[nodiscard]] double support() const { return h_; }
  [[nodiscard]] double inv_support() const { return inv_h_; }
  /// F = f_coef (1 - q)^2 (Lucy) or f_coef (1 - q)^3 (Wendland C2).
  [[nodiscard]] double f_coef() const { return f_coef_; }
  [[nodiscard]] double sqrt_f_coef() const { return sqrt_f_coef_; }
  [[nodiscard]] int dimension() const { return dim_; }
  [[nodiscard]] KernelType type() const { return type_; }
  /// W(0) [1/length^d] (self contribution to a summation density).
  [[nodiscard]] double w0() const { return alpha_; }

 private:
  double h_ = 1.0, inv_h_ = 1.0, alpha_ = 1.0, f_coef_ = 1.0, sqrt_f_coef_ = 1.0;
  int dim_ = 3;
  KernelType type_ = KernelType::kLucy;
};

}  // namespace sadr::fluid
