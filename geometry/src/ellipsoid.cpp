// SPDX-License-Identifier: MIT
// Ellipse and ellipsoid with the exact Euclidean distance: the closest point from D. Eberly,
// "Distance from a point to an ellipse, an ellipsoid, or a hyperellipsoid" (Geometric Tools,
// 2013), bisection on the monotone root equation, so the distance is exact to rounding.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

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
