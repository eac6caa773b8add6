// SPDX-License-Identifier: MIT
// 2D polygon (exact distance to its edges, sign by the even-odd rule) and its extrusion along z.
#include <cmath>
#include <string>

#include "sadr/common/status.hpp"
#include "sadr/geometry/shape.hpp"
#include "shape_util.hpp"

namespace sadr::geometry {
namespace {

class Polygon final : public Shape {
 public:
  explicit Polygon(std::vector<Vec3> v) : v_(std::move(v)) {
    for (auto& p : v_) p.z = 0;
    for (const auto& p : v_) box_.add(p);
    double a = 0;
    for (std::size_t i = 0, j = v_.size() - 1; i < v_.size(); j = i++) {
      a += v_[j].x * v_[i].y - v_[i].x * v_[j].y;
    }
    area_ = 0.5 * std::abs(a);
    for (std::size_t i = 0, j = v_.size() - 1; i < v_.size(); j = i++)
      perimeter_ += norm(v_[i] - v_[j]);
  }
  int dimension() const override { return 2; }
  double signed_distance(Vec3 p) const override {
    p.z = 0;
    const Vec3 q = nearest(p);
    return inside_even_odd(p) ? -norm(p - q) : norm(p - q);
  }
  Vec3 normal(Vec3 p) const override {
    p.z = 0;
    const Vec3 d = p - nearest(p);
    if (norm2(d) > 0) return inside_even_odd(p) ? normalized(-d) : normalized(d);
    return Shape::normal(p);
  }
  bool inside(Vec3 p) const override { return inside_even_odd(p); }
  Aabb bounds() const override { return box_; }
  std::optional<double> exact_volume() const override { return area_; }
  std::optional<double> exact_area() const override { return perimeter_; }
  double area() const { return area_; }
  double perimeter() const { return perimeter_; }

 private:
  Vec3 nearest(Vec3 p) const {
    Vec3 best;
    double best_d2 = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0, j = v_.size() - 1; i < v_.size(); j = i++) {
      const Vec3 e = v_[i] - v_[j], w = p - v_[j];
      const double t = std::clamp(dot(w, e) / dot(e, e), 0.0, 1.0);
      const Vec3 q = v_[j] + t * e;
      const double d2 = norm2(p - q);
      if (d2 < best_d2) {
        best_d2 = d2;
        best = q;
      }
    }
    return best;
  }
  bool inside_even_odd(Vec3 p) const {
    bool in = false;
    for (std::size_t i = 0, j = v_.size() - 1; i < v_.size(); j = i++) {
      const Vec3 a = v_[j], b = v_[i];
      if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y)) {
        in = !in;
      }
    }
    return in;
  }
  std::vector<Vec3> v_;
  Aabb box_;
  double area_ = 0;
  double perimeter_ = 0;
};

class Extrusion final : public Shape {
 public:
  Extrusion(std::shared_ptr<const Polygon> poly, double z0, double z1)
      : poly_(std::move(poly)), zm_(0.5 * (z0 + z1)), hz_(0.5 * (z1 - z0)) {}
  int dimension() const override { return 3; }
  double signed_distance(Vec3 p) const override {
    const double wx = poly_->signed_distance(p), wy = std::abs(p.z - zm_) - hz_;
    return std::min(std::max(wx, wy), 0.0) + std::hypot(std::max(wx, 0.0), std::max(wy, 0.0));
  }
  Aabb bounds() const override {
    Aabb b = poly_->bounds();
    b.lo.z = zm_ - hz_;
    b.hi.z = zm_ + hz_;
    return b;
  }
  std::optional<double> exact_volume() const override { return poly_->area() * 2 * hz_; }
  std::optional<double> exact_area() const override {
    return poly_->perimeter() * 2 * hz_ + 2 * poly_->area();
  }

 private:
  std::shared_ptr<const Polygon> poly_;
  double zm_, hz_;
};

std::shared_ptr<const Polygon> checked_polygon(std::vector<Vec3> v, const std::string& what) {
  if (v.size() < 3) {
    throw InvalidArgument(what + ": a polygon needs at least 3 vertices, got " +
                          std::to_string(v.size()));
  }
  for (std::size_t i = 0; i < v.size(); ++i) {
    require_finite(v[i], what + ".vertices[" + std::to_string(i) + "]");
  }
  auto poly = std::make_shared<const Polygon>(std::move(v));
  if (!(poly->area() > 0)) throw InvalidArgument(what + ": the polygon has zero area");
  return poly;
}

}  // namespace

ShapePtr make_polygon(std::vector<Vec3> vertices) {
  return checked_polygon(std::move(vertices), "polygon");
}

ShapePtr make_extrusion(std::vector<Vec3> vertices, double z0, double z1) {
  auto poly = checked_polygon(std::move(vertices), "extrusion");
  if (!(z1 > z0) || !std::isfinite(z0) || !std::isfinite(z1)) {
    throw InvalidArgument("extrusion: need finite z0 < z1, got z0 = " + format_value(z0) +
                          ", z1 = " + format_value(z1));
  }
  return std::make_shared<Extrusion>(std::move(poly), z0, z1);
}

}  // namespace sadr::geometry
