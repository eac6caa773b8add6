// SPDX-License-Identifier: MIT
/// \file reference_solutions.hpp
/// Closed-form references: case 1 (step, erf images), 2 (Dirichlet series), 3 (Neumann
/// series), 5 (Poiseuille start-up), and the scaled error norms (scaled L2 = weighted RMS /
/// scale, scaled Linf = max / scale). Checked against the CSV spot values in
/// reference_solutions_test.cpp.
#pragma once

#include <cmath>
#include <numbers>
#include <vector>

namespace sadr::fluid::test {

/// Case 1 with no-flux walls at a, b (image sum of the even reflection):
/// C1 = sum_n 1/2 [erf((x - 2nL - 2a)/s) - erf((x - 2nL)/s)], s = 2 sqrt(D t).
inline double step_neumann(double x, double t, double d, double a = -50.0, double b = 50.0) {
  const double l = b - a, s = 2.0 * std::sqrt(d * t);
  double c = 0;
  for (int n = -20; n <= 20; ++n) {
    c += 0.5 * (std::erf((x - 2 * n * l - 2 * a) / s) - std::erf((x - 2 * n * l) / s));
  }
  return c;
}

/// Case 2: C = C0 x/L + (2 C0/pi) sum (-1)^n/n sin(n pi x/L) exp(-D n^2 pi^2 t/L^2), or images
/// at early times (D t / L^2 < 0.05).
inline double dirichlet_exact(double x, double t, double d = 3.87, double l = 100.0,
                              double c0 = 1.0) {
  const double pi = std::numbers::pi;
  if (d * t / (l * l) < 0.05) {
    const double s = 2.0 * std::sqrt(d * t);
    double c = 0;
    for (int n = 0; n < 50; ++n)
      c += std::erfc(((2 * n + 1) * l - x) / s) - std::erfc(((2 * n + 1) * l + x) / s);
    return c0 * c;
  }
  double c = c0 * x / l;
  for (int n = 1; n < 4000; ++n) {
    const double e = std::exp(-d * n * n * pi * pi * t / (l * l));
    if (e < 1e-300) break;
    c += 2 * c0 / pi * ((n % 2) ? -1.0 : 1.0) / n * std::sin(n * pi * x / l) * e;
  }
  return c;
}

/// Case 3: inward flux D Lambda at x = 0, C(L) = 0:
/// C = sum_k (-1)^k g(x - 2kL), g(x) = Lambda [2 sqrt(Dt/pi) e^{-x^2/4Dt} - |x| erfc(|x|/(2
/// sqrt(Dt)))].
inline double neumann_exact(double x, double t, double d = 3.87, double l = 100.0,
                            double lambda = 0.01) {
  const double pi = std::numbers::pi;
  if (!std::isfinite(t)) return lambda * (l - x);
  auto g = [&](double y) {
    const double ay = std::fabs(y);
    return lambda * (2 * std::sqrt(d * t / pi) * std::exp(-y * y / (4 * d * t)) -
                     ay * std::erfc(ay / (2 * std::sqrt(d * t))));
  };
  if (d * t / (l * l) > 0.5) {  // Fourier form converges fast at late times
    double c = lambda * (l - x);
    for (int n = 1; n < 2000; ++n) {
      const double mu = (2 * n - 1) * pi / (2 * l);
      const double e = std::exp(-d * mu * mu * t);
      if (e < 1e-300) break;
      c -= 2 * lambda / (l * mu * mu) * std::cos(mu * x) * e;
    }
    return c;
  }
  double c = 0;
  for (int k = -30; k <= 30; ++k) c += ((k % 2) ? -1.0 : 1.0) * g(x - 2 * k * l);
  return c;
}

/// Case 5 (sign-corrected Morris 1997 start-up series): u(y, t) for body force g, viscosity nu.
inline double poiseuille_exact(double y, double t, double g = 2e-4, double nu = 1e-6,
                               double h = 1e-3) {
  const double pi = std::numbers::pi;
  double u = g / (2 * nu) * y * (h - y);
  if (!std::isfinite(t)) return u;
  for (int n = 0; n < 2000; ++n) {
    const double k = 2 * n + 1;
    const double e = std::exp(-k * k * pi * pi * nu * t / (h * h));
    if (e < 1e-300) break;
    u -= 4 * g * h * h / (nu * pi * pi * pi * k * k * k) * std::sin(k * pi * y / h) * e;
  }
  return u;
}

/// Scaled norms of section 8 with weights w (volumes): returns {scaled L2, scaled Linf}.
inline std::pair<double, double> scaled_norms(const std::vector<double>& u,
                                              const std::vector<double>& ref,
                                              const std::vector<double>& w, double scale) {
  double num = 0, den = 0, linf = 0;
  for (std::size_t i = 0; i < u.size(); ++i) {
    const double e = u[i] - ref[i];
    num += w[i] * e * e;
    den += w[i];
    linf = std::max(linf, std::fabs(e));
  }
  return {std::sqrt(num / den) / scale, linf / scale};
}

}  // namespace sadr::fluid::test
