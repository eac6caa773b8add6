// SPDX-License-Identifier: MIT
/// \file tdpd_forces.hpp
/// Pair weights of tDPD (li2015 eqs 3-6) and their analytic integrals used by the
/// stability limits. Everything here is header-only and branch-light for the pair loop.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sadr::fluid::tdpd {

/// Weights of one pair at distance r < r_c [length].
struct PairWeights {
  double w_c;  ///< 1 - r/r_c (conservative)
  double w_r;  ///< (1 - r/r_c)^(s1/2) (random); w_D = w_r^2
};

/// @param q r / r_c in [0, 1); @param half_s1 s1 / 2.
inline PairWeights weights(double q, double half_s1) {
  const double wc = 1.0 - q;
  return {wc, half_s1 == 0.5 ? std::sqrt(wc) : std::pow(wc, half_s1)};
}

/// Fickian weight w_DC = (1 - r/r_cc)^2 (li2015 eq 6, s2 = 2); 0 beyond r_cc.
inline double flux_weight(double r, double inv_r_cc) {
  const double s = 1.0 - r * inv_r_cc;
  return s > 0.0 ? s * s : 0.0;
}

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
