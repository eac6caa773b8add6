// SPDX-License-Identifier: MIT
/// \file tait_eos.hpp
/// Tait equation of state (docs/method.md section 2; Monaghan 1994, Morris 1997):
/// \f$ P = \frac{\rho_0 c_0^2}{\gamma}\left[(\rho/\rho_0)^\gamma - 1\right] \f$, gamma = 7.
#pragma once

#include <cmath>

namespace sadr::fluid {

class TaitEos {
 public:
  TaitEos() = default;
  /// @param rho0 reference density [mass/length^d]; @param c0 reference sound speed [length/time].
  TaitEos(double rho0, double c0) : inv_rho0_(1.0 / rho0), b_(rho0 * c0 * c0 / 7.0) {}
  /// Pressure [mass/(length^(d-2) time^2)] at density rho.
  [[nodiscard]] double pressure(double rho) const {
    const double t = rho * inv_rho0_;
    const double t3 = t * t * t;
    return b_ * (t3 * t3 * t - 1.0);
  }
  /// The inverse law: the density at pressure p, rho_0 (1 + p/B)^(1/gamma), with 1 + p/B
  /// floored at `min_ratio` (> 0; a tension beyond -B has no density).
  [[nodiscard]] double density(double p, double min_ratio) const {
    const double t = 1.0 + p / b_;
    return std::pow(t > min_ratio ? t : min_ratio, 1.0 / 7.0) / inv_rho0_;
  }
  /// B = rho0 c0^2 / gamma.
  [[nodiscard]] double stiffness() const { return b_; }

 private:
  double inv_rho0_ = 1.0, b_ = 1.0 / 7.0;
};

}  // namespace sadr::fluid
