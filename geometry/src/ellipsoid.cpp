// SPDX-License-Identifier: MIT
// Ellipse and ellipsoid with the exact Euclidean distance: the closest point from D. Eberly,
// "Distance from a point to an ellipse, an ellipsoid, or a hyperellipsoid" (Geometric Tools,
// 2013), bisection on the monotone root equation, so the distance is exact to rounding.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "sadr/geometry/shape.hpp"
#include "shape_util.hpp"

namespace sadr::geometry {
namespace {

double bisect(double s0, double s1, auto&& g) {
  for (int i = 0; i < 2200; ++i) {
    const double s = 0.5 * (s0 + s1);
    if (s == s0 || s == s1) return s;
    const double v = g(s);
    if (v > 0) {
      s0 = s;
    } else if (v < 0) {
      s1 = s;
    } else {
      return s;
    }
  }
  return 0.5 * (s0 + s1);
}

/// Closest point x on the ellipse with semi-axes e0 >= e1 > 0 to y (y0, y1 >= 0).
std::array<double, 2> closest2(double e0, double e1, double y0, double y1) {
  if (y1 > 0) {
    if (y0 > 0) {
      const double z0 = y0 / e0, z1 = y1 / e1, g = z0 * z0 + z1 * z1 - 1;
      if (g == 0) return {y0, y1};
      const double r0 = (e0 / e1) * (e0 / e1), n0 = r0 * z0;
      const double s = bisect(z1 - 1, g < 0 ? 0.0 : std::hypot(n0, z1) - 1, [&](double t) {
        const double a = n0 / (t + r0), b = z1 / (t + 1);
        return a * a + b * b - 1;
      });
      return {r0 * y0 / (s + r0), y1 / (s + 1)};
    }
    return {0, e1};
  }
  const double numer0 = e0 * y0, denom0 = e0 * e0 - e1 * e1;
  if (numer0 < denom0) {
    const double xde0 = numer0 / denom0;
    return {e0 * xde0, e1 * std::sqrt(1 - xde0 * xde0)};
  }
  return {e0, 0};
}

/// Closest point on the ellipsoid with e0 >= e1 >= e2 > 0 to y (all y >= 0).
std::array<double, 3> closest3(const std::array<double, 3>& e, const std::array<double, 3>& y) {
  if (y[2] > 0) {
    if (y[1] > 0) {
      if (y[0] > 0) {
        const double z0 = y[0] / e[0], z1 = y[1] / e[1], z2 = y[2] / e[2];
        const double g = z0 * z0 + z1 * z1 + z2 * z2 - 1;
        if (g == 0) return y;
        const double r0 = (e[0] / e[2]) * (e[0] / e[2]), r1 = (e[1] / e[2]) * (e[1] / e[2]);
        const double n0 = r0 * z0, n1 = r1 * z1;
        const double hi = g < 0 ? 0.0 : std::sqrt(n0 * n0 + n1 * n1 + z2 * z2) - 1;
        const double s = bisect(z2 - 1, hi, [&](double t) {
          const double a = n0 / (t + r0), b = n1 / (t + r1), c = z2 / (t + 1);
          return a * a + b * b + c * c - 1;
        });
        return {r0 * y[0] / (s + r0), r1 * y[1] / (s + r1), y[2] / (s + 1)};
      }
      const auto x = closest2(e[1], e[2], y[1], y[2]);
      return {0, x[0], x[1]};
    }
    if (y[0] > 0) {
      const auto x = closest2(e[0], e[2], y[0], y[2]);
      return {x[0], 0, x[1]};
    }
    return {0, 0, e[2]};
  }
  const double denom0 = e[0] * e[0] - e[2] * e[2], denom1 = e[1] * e[1] - e[2] * e[2];
  const double numer0 = e[0] * y[0], numer1 = e[1] * y[1];
  if (numer0 < denom0 && numer1 < denom1) {
    const double xde0 = numer0 / denom0, xde1 = numer1 / denom1;
    const double discr = 1 - xde0 * xde0 - xde1 * xde1;
    if (discr > 0) return {e[0] * xde0, e[1] * xde1, e[2] * std::sqrt(discr)};
  }
  const auto x = closest2(e[0], e[1], y[0], y[1]);
  return {x[0], x[1], 0};
}

/// Trapezoid rule over one period of a smooth periodic f, doubling the points until two
/// estimates agree to round-off (it converges geometrically for an analytic f).
double periodic_integral(auto&& f) {
  constexpr double two_pi = 2 * std::numbers::pi;
  double prev = 0;
  for (int n = 32; n <= (1 << 22); n *= 2) {
    double sum = 0;
    for (int k = 0; k < n; ++k) sum += f(two_pi * k / n);
    const double est = sum * two_pi / n;
    if (n > 32 && std::abs(est - prev) <= 1e-14 * std::abs(est)) return est;
    prev = est;
  }
  return prev;
}

/// Gauss-Legendre nodes and weights on [-1, 1] (Newton on P_n from the Chebyshev guesses).
void gauss_legendre(int n, std::vector<double>& x, std::vector<double>& w) {
  x.assign(static_cast<std::size_t>(n), 0.0);
  w.assign(static_cast<std::size_t>(n), 0.0);
  for (int i = 0; i < n; ++i) {
    double z = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    double dp = 1;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1, p1 = z;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (z * p1 - p0) / (z * z - 1);
      const double dz = p1 / dp;
      z -= dz;
      if (std::abs(dz) < 1e-16) break;
    }
    x[static_cast<std::size_t>(i)] = z;
    w[static_cast<std::size_t>(i)] = 2 / ((1 - z * z) * dp * dp);
  }
}

/// Ellipse perimeter: the integral of |r'(t)| = sqrt(a^2 sin^2 t + b^2 cos^2 t) over a period.
double ellipse_perimeter(double a, double b) {
  return periodic_integral([&](double t) {
    const double s = std::sin(t), c = std::cos(t);
    return std::sqrt(a * a * s * s + b * b * c * c);
  });
}

/// Ellipsoid area over (u, phi), r = (a s cos phi, b s sin phi, c u), s = sqrt(1 - u^2):
/// |r_u x r_phi| = sqrt(s^2 c^2 (b^2 cos^2 phi + a^2 sin^2 phi) + a^2 b^2 u^2), smooth on
/// [-1, 1] x period; Gauss-Legendre in u (doubling until round-off), trapezoid in phi.
double ellipsoid_area(double a, double b, double c) {
  double prev = 0;
  std::vector<double> x, w;
  for (int n = 16; n <= 4096; n *= 2) {
    gauss_legendre(n, x, w);
    double est = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      const double u = x[i], s2 = 1 - u * u;
      est += w[i] * periodic_integral([&](double ph) {
               const double cp = std::cos(ph), sp = std::sin(ph);
               return std::sqrt(s2 * c * c * (b * b * cp * cp + a * a * sp * sp) +
                                a * a * b * b * u * u);
             });
    }
    if (n > 16 && std::abs(est - prev) <= 1e-13 * std::abs(est)) return est;
    prev = est;
  }
  return prev;
}

class Ellipsoid final : public Shape {
 public:
  Ellipsoid(Vec3 c, Vec3 radii, int dim) : c_(c), radii_(radii), dim_(dim) {
    for (int a = 0; a < 3; ++a) order_[a] = a;
    // Axes sorted by decreasing semi-axis (the 2D case sorts x, y only).
    std::sort(order_.begin(), order_.begin() + dim_,
              [&](int i, int j) { return radii_[i] > radii_[j]; });
  }
  int dimension() const override { return dim_; }
  double signed_distance(Vec3 p) const override {
    Vec3 x;
    const Vec3 d = rel(p);
    const double dist = norm(d - (x = closest(d)));
    return is_inside(d) ? -dist : dist;
  }
  Vec3 normal(Vec3 p) const override {
    const Vec3 d = rel(p);
    const Vec3 x = closest(d);
    const Vec3 v = d - x;
    if (norm(v) > 1e-12 * radii_[order_[0]]) return is_inside(d) ? normalized(-v) : normalized(v);
    Vec3 g;
    for (int a = 0; a < dim_; ++a) g[a] = x[a] / (radii_[a] * radii_[a]);
    return normalized(g);
  }
  Aabb bounds() const override {
    Vec3 r = radii_;
    if (dim_ == 2) r.z = 0;
    return {c_ - r, c_ + r};
  }
  std::optional<double> exact_volume() const override {
    constexpr double pi = std::numbers::pi;
    return dim_ == 2 ? pi * radii_.x * radii_.y : 4.0 / 3.0 * pi * radii_.x * radii_.y * radii_.z;
  }
  std::optional<double> exact_area() const override {
    return dim_ == 2 ? ellipse_perimeter(radii_.x, radii_.y)
                     : ellipsoid_area(radii_.x, radii_.y, radii_.z);
  }

 private:
  Vec3 rel(Vec3 p) const {
    Vec3 d = p - c_;
    if (dim_ == 2) d.z = 0;
    return d;
  }
  bool is_inside(Vec3 d) const {
    double s = 0;
    for (int a = 0; a < dim_; ++a) s += (d[a] / radii_[a]) * (d[a] / radii_[a]);
    return s < 1;
  }
  /// Closest surface point to d (relative to the centre), in the original frame.
  Vec3 closest(Vec3 d) const {
    std::array<double, 3> e{}, y{};
    for (int k = 0; k < dim_; ++k) {
      e[k] = radii_[order_[k]];
      y[k] = std::abs(d[order_[k]]);
    }
    std::array<double, 3> x{};
    if (dim_ == 2) {
      const auto x2 = closest2(e[0], e[1], y[0], y[1]);
      x = {x2[0], x2[1], 0};
    } else {
      x = closest3(e, y);
    }
    Vec3 out;
    for (int k = 0; k < dim_; ++k) out[order_[k]] = std::copysign(x[k], d[order_[k]]);
    return out;
  }
  Vec3 c_, radii_;
  int dim_;
  std::array<int, 3> order_{};
};

}  // namespace

ShapePtr make_ellipsoid(Vec3 center, Vec3 radii, int dimension) {
  require_dimension(dimension, "ellipsoid");
  require_finite(center, "ellipsoid.center");
  require_positive(radii.x, "ellipsoid.radii.x");
  require_positive(radii.y, "ellipsoid.radii.y");
  if (dimension == 3) require_positive(radii.z, "ellipsoid.radii.z");
  if (dimension == 2) center.z = 0;
  return std::make_shared<Ellipsoid>(center, radii, dimension);
}

}  // namespace sadr::geometry
