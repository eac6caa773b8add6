// SPDX-License-Identifier: MIT
/// \file vec.hpp
/// A 3-vector and an axis-aligned box, the geometry library's only value types. 2D geometry uses
/// the x and y components and leaves z at 0.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

namespace sadr::geometry {

struct Vec3 {
  double x = 0, y = 0, z = 0;
  double& operator[](int a) { return a == 0 ? x : (a == 1 ? y : z); }
  double operator[](int a) const { return a == 0 ? x : (a == 1 ? y : z); }
};

inline Vec3 operator+(Vec3 a, Vec3 b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline Vec3 operator-(Vec3 a, Vec3 b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline Vec3 operator-(Vec3 a) {
  return {-a.x, -a.y, -a.z};
}
inline Vec3 operator*(double s, Vec3 a) {
  return {s * a.x, s * a.y, s * a.z};
}
inline Vec3 operator*(Vec3 a, double s) {
  return s * a;
}
inline Vec3 operator/(Vec3 a, double s) {
  return {a.x / s, a.y / s, a.z / s};
}
inline Vec3& operator+=(Vec3& a, Vec3 b) {
  return a = a + b;
}
inline Vec3& operator-=(Vec3& a, Vec3 b) {
  return a = a - b;
}
inline double dot(Vec3 a, Vec3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm2(Vec3 a) {
  return dot(a, a);
}
inline double norm(Vec3 a) {
  return std::sqrt(dot(a, a));
}
/// a / |a|, or (0, 0, 0) for a zero vector.
inline Vec3 normalized(Vec3 a) {
  const double n = norm(a);
  return n > 0 ? a / n : Vec3{};
}
inline Vec3 cwise_min(Vec3 a, Vec3 b) {
  return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
inline Vec3 cwise_max(Vec3 a, Vec3 b) {
  return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}
inline Vec3 cwise_abs(Vec3 a) {
  return {std::abs(a.x), std::abs(a.y), std::abs(a.z)};
}
inline bool all_finite(Vec3 a) {
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}

/// Axis-aligned bounding box; empty() until a point is added.
struct Aabb {
  Vec3 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
          std::numeric_limits<double>::infinity()};
  Vec3 hi{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
          -std::numeric_limits<double>::infinity()};

  [[nodiscard]] bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  void add(Vec3 p) {
    lo = cwise_min(lo, p);
    hi = cwise_max(hi, p);
  }
  void add(const Aabb& b) {
    lo = cwise_min(lo, b.lo);
    hi = cwise_max(hi, b.hi);
  }
  [[nodiscard]] Vec3 center() const { return 0.5 * (lo + hi); }
  [[nodiscard]] Vec3 extent() const { return hi - lo; }
  [[nodiscard]] bool contains(Vec3 p) const {
    return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z && p.z <= hi.z;
  }
  /// Squared distance from p to the box (0 inside).
  [[nodiscard]] double distance2(Vec3 p) const {
    const Vec3 d = cwise_max(cwise_max(lo - p, p - hi), Vec3{});
    return norm2(d);
  }
  /// The box grown by r on every side.
  [[nodiscard]] Aabb inflated(double r) const { return {lo - Vec3{r, r, r}, hi + Vec3{r, r, r}}; }
};

inline Aabb intersect(const Aabb& a, const Aabb& b) {
  return {cwise_max(a.lo, b.lo), cwise_min(a.hi, b.hi)};
}

}  // namespace sadr::geometry
