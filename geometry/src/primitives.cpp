// SPDX-License-Identifier: MIT
// Box, sphere/disk, cylinder, capsule and torus with exact signed distances.
#include <cmath>
#include <numbers>
#include <string>

#include "sadr/common/status.hpp"
#include "sadr/geometry/shape.hpp"
#include "shape_util.hpp"

namespace sadr::geometry {

Vec3 Shape::normal(Vec3 p) const {
  const Aabb b = bounds();
  const double e = 1e-6 * std::max(norm(b.extent()), 1e-300);
  Vec3 g;
  for (int a = 0; a < dimension(); ++a) {
    Vec3 dp;
    dp[a] = e;
    g[a] = signed_distance(p + dp) - signed_distance(p - dp);
  }
  return normalized(g);
}

namespace {

constexpr double kPi = std::numbers::pi;

class Box final : public Shape {
 public:
  Box(Vec3 lo, Vec3 hi, int dim) : c_(0.5 * (lo + hi)), half_(0.5 * (hi - lo)), dim_(dim) {
    if (dim_ == 2) half_.z = 0;
  }
  int dimension() const override { return dim_; }
  double signed_distance(Vec3 p) const override {
    Vec3 q = cwise_abs(p - c_) - half_;
    if (dim_ == 2) q.z = -std::numeric_limits<double>::infinity();
    const Vec3 qp = cwise_max(q, Vec3{});
    return norm(qp) + std::min(std::max(q.x, std::max(q.y, q.z)), 0.0);
  }
  Aabb bounds() const override { return {c_ - half_, c_ + half_}; }
  std::optional<double> exact_volume() const override {
    return dim_ == 2 ? 4 * half_.x * half_.y : 8 * half_.x * half_.y * half_.z;
  }
  std::optional<double> exact_area() const override {
    return dim_ == 2 ? 4 * (half_.x + half_.y)
                     : 8 * (half_.x * half_.y + half_.y * half_.z + half_.z * half_.x);
  }

 private:
  Vec3 c_, half_;
  int dim_;
};

class Sphere final : public Shape {
 public:
  Sphere(Vec3 c, double r, int dim) : c_(c), r_(r), dim_(dim) {}
  int dimension() const override { return dim_; }
  double signed_distance(Vec3 p) const override { return norm(rel(p)) - r_; }
  Vec3 normal(Vec3 p) const override {
    const Vec3 d = rel(p);
    return norm2(d) > 0 ? normalized(d) : Vec3{1, 0, 0};
  }
  Aabb bounds() const override {
    const Vec3 r{r_, r_, dim_ == 2 ? 0.0 : r_};
    return {c_ - r, c_ + r};
  }
  std::optional<double> exact_volume() const override {
    return dim_ == 2 ? kPi * r_ * r_ : 4.0 / 3.0 * kPi * r_ * r_ * r_;
  }
  std::optional<double> exact_area() const override {
    return dim_ == 2 ? 2 * kPi * r_ : 4 * kPi * r_ * r_;
  }

 private:
  Vec3 rel(Vec3 p) const {
    Vec3 d = p - c_;
    if (dim_ == 2) d.z = 0;
    return d;
  }
  Vec3 c_;
  double r_;
  int dim_;
};

/// Quilez's exact capped-cylinder distance (iquilezles.org/articles/distfunctions).
class Cylinder final : public Shape {
 public:
  Cylinder(Vec3 a, Vec3 b, double r) : a_(a), b_(b), r_(r) {}
  int dimension() const override { return 3; }
  double signed_distance(Vec3 p) const override {
    const Vec3 ba = b_ - a_, pa = p - a_;
    const double baba = dot(ba, ba), paba = dot(pa, ba);
    const double x = norm(pa * baba - ba * paba) - r_ * baba;
    const double y = std::abs(paba - baba * 0.5) - baba * 0.5;
    const double x2 = x * x, y2 = y * y * baba;
    const double d =
        (std::max(x, y) < 0.0) ? -std::min(x2, y2) : ((x > 0.0 ? x2 : 0.0) + (y > 0.0 ? y2 : 0.0));
    return std::copysign(std::sqrt(std::abs(d)), d) / baba;
  }
  Aabb bounds() const override {
    Aabb b;
    b.add(a_);
    b.add(b_);
    return b.inflated(r_);
  }
  std::optional<double> exact_volume() const override { return kPi * r_ * r_ * norm(b_ - a_); }
  std::optional<double> exact_area() const override {
    return 2 * kPi * r_ * norm(b_ - a_) + 2 * kPi * r_ * r_;
  }

 private:
  Vec3 a_, b_;
  double r_;
};

class Capsule final : public Shape {
 public:
  Capsule(Vec3 a, Vec3 b, double r, int dim) : a_(a), b_(b), r_(r), dim_(dim) {}
  int dimension() const override { return dim_; }
  double signed_distance(Vec3 p) const override { return norm(offset(p)) - r_; }
  Vec3 normal(Vec3 p) const override {
    const Vec3 d = offset(p);
    if (norm2(d) > 0) return normalized(d);
    return any_perpendicular(b_ - a_);
  }
  Aabb bounds() const override {
    Aabb b;
    b.add(a_);
    b.add(b_);
    b = b.inflated(r_);
    if (dim_ == 2) b.lo.z = b.hi.z = 0;
    return b;
  }
  std::optional<double> exact_volume() const override {
    const double len = norm(b_ - a_);
    return dim_ == 2 ? 2 * r_ * len + kPi * r_ * r_
                     : kPi * r_ * r_ * len + 4.0 / 3.0 * kPi * r_ * r_ * r_;
  }
  std::optional<double> exact_area() const override {
    const double len = norm(b_ - a_);
    return dim_ == 2 ? 2 * len + 2 * kPi * r_ : 2 * kPi * r_ * len + 4 * kPi * r_ * r_;
  }

 private:
  Vec3 offset(Vec3 p) const {
    if (dim_ == 2) p.z = 0;
    const Vec3 ba = b_ - a_, pa = p - a_;
    const double bb = dot(ba, ba);
    const double t = bb > 0 ? std::clamp(dot(pa, ba) / bb, 0.0, 1.0) : 0.0;
    return pa - t * ba;
  }
  Vec3 a_, b_;
  double r_;
  int dim_;
};

class Torus final : public Shape {
 public:
  Torus(Vec3 c, double big_r, double small_r) : c_(c), big_r_(big_r), small_r_(small_r) {}
  int dimension() const override { return 3; }
  double signed_distance(Vec3 p) const override { return norm(from_ring(p)) - small_r_; }
  Vec3 normal(Vec3 p) const override {
    const Vec3 d = from_ring(p);
    return norm2(d) > 0 ? normalized(d) : Vec3{0, 0, 1};
  }
  Aabb bounds() const override {
    const double e = big_r_ + small_r_;
    return {c_ - Vec3{e, e, small_r_}, c_ + Vec3{e, e, small_r_}};
  }
  std::optional<double> exact_volume() const override {
    return 2 * kPi * kPi * big_r_ * small_r_ * small_r_;
  }
  std::optional<double> exact_area() const override { return 4 * kPi * kPi * big_r_ * small_r_; }

 private:
  /// p minus its nearest point on the ring.
  Vec3 from_ring(Vec3 p) const {
    const Vec3 d = p - c_;
    const double rho = std::hypot(d.x, d.y);
    const Vec3 ring =
        rho > 0 ? Vec3{big_r_ * d.x / rho, big_r_ * d.y / rho, 0} : Vec3{big_r_, 0, 0};
    return d - ring;
  }
  Vec3 c_;
  double big_r_, small_r_;
};

}  // namespace

ShapePtr make_box(Vec3 lo, Vec3 hi, int dimension) {
  require_dimension(dimension, "box");
  require_finite(lo, "box.lo");
  require_finite(hi, "box.hi");
  for (int a = 0; a < dimension; ++a) {
    if (!(hi[a] > lo[a])) {
      throw InvalidArgument("box: hi must exceed lo on every axis; axis " + std::to_string(a) +
                            " has lo = " + format_value(lo[a]) + ", hi = " + format_value(hi[a]));
    }
  }
  return std::make_shared<Box>(lo, hi, dimension);
}

ShapePtr make_sphere(Vec3 center, double radius, int dimension) {
  require_dimension(dimension, "sphere");
  require_finite(center, "sphere.center");
  require_positive(radius, "sphere.radius");
  if (dimension == 2) center.z = 0;
  return std::make_shared<Sphere>(center, radius, dimension);
}

ShapePtr make_cylinder(Vec3 a, Vec3 b, double radius) {
  require_finite(a, "cylinder.a");
  require_finite(b, "cylinder.b");
  require_positive(radius, "cylinder.radius");
  require_positive(norm(b - a), "cylinder length |b - a|");
  return std::make_shared<Cylinder>(a, b, radius);
}

ShapePtr make_capsule(Vec3 a, Vec3 b, double radius, int dimension) {
  require_dimension(dimension, "capsule");
  require_finite(a, "capsule.a");
  require_finite(b, "capsule.b");
  require_positive(radius, "capsule.radius");
  if (dimension == 2) a.z = b.z = 0;
  return std::make_shared<Capsule>(a, b, radius, dimension);
}

ShapePtr make_torus(Vec3 center, double major_radius, double minor_radius) {
  require_finite(center, "torus.center");
  require_positive(minor_radius, "torus.minor_radius");
  if (!(major_radius > minor_radius)) {
    throw InvalidArgument("torus.major_radius must exceed minor_radius (" +
                          format_value(minor_radius) + "), got " + format_value(major_radius));
  }
  return std::make_shared<Torus>(center, major_radius, minor_radius);
}

}  // namespace sadr::geometry
