// SPDX-License-Identifier: MIT
/// \file tdpd_forces.hpp
/// Analytic integrals of the tDPD pair weights (li2015 eqs 3-6) used by the stability limits,
/// and the sound speed.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sadr::fluid::tdpd {

// The pair weights themselves (w_C, w_R = w_C^(s1/2), w_DC) are evaluated in the SIMD pair
// block, tdpd_pair_block.cpp.

/// Integral of (1 - r/R)^p over a d-ball of radius R [length^d] (d = 1, 2, 3, p > -1).
inline double ball_integral(int d, double radius, double p) {
  const double pi = std::numbers::pi;
  if (d == 1) return 2.0 * radius / (p + 1.0);
  if (d == 2) return 2.0 * pi * radius * radius / ((p + 1.0) * (p + 2.0));
  return 8.0 * pi * radius * radius * radius / ((p + 1.0) * (p + 2.0) * (p + 3.0));
}

/// Groot & Warren 1997 equation of state p = rho k_B T + alpha a rho^2 (alpha = 0.101):
/// isothermal sound speed [length/time] for unit mass.
inline double sound_speed(double rho, double kbt, double a) {
  return std::sqrt(std::max(kbt + 2.0 * 0.101 * a * rho, 1e-300));
}

}  // namespace sadr::fluid::tdpd
