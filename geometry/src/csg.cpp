// SPDX-License-Identifier: MIT
// Transforms (translate, rotate, scale) and CSG (union, intersection, difference).
#include <cmath>
#include <limits>
#include <string>

#include "sadr/common/status.hpp"
#include "sadr/geometry/shape.hpp"
#include "shape_util.hpp"

namespace sadr::geometry {
namespace {

Aabb transformed_bounds(const Aabb& b, int dim, auto&& map) {
  Aabb out;
  for (int c = 0; c < (dim == 2 ? 4 : 8); ++c) {
    out.add(
        map(Vec3{(c & 1) ? b.hi.x : b.lo.x, (c & 2) ? b.hi.y : b.lo.y, (c & 4) ? b.hi.z : b.lo.z}));
  }
  return out;
}

class Translated final : public Shape {
 public:
  Translated(ShapePtr s, Vec3 t) : s_(std::move(s)), t_(t) {}
  int dimension() const override { return s_->dimension(); }
  double signed_distance(Vec3 p) const override { return s_->signed_distance(p - t_); }
  double signed_distance_bounded(Vec3 p, double limit) const override {
    return s_->signed_distance_bounded(p - t_, limit);
  }
  Vec3 normal(Vec3 p) const override { return s_->normal(p - t_); }
  bool inside(Vec3 p) const override { return s_->inside(p - t_); }
  Aabb bounds() const override {
    const Aabb b = s_->bounds();
    return {b.lo + t_, b.hi + t_};
  }
  std::optional<double> exact_volume() const override { return s_->exact_volume(); }
  std::optional<double> exact_area() const override { return s_->exact_area(); }

 private:
  ShapePtr s_;
  Vec3 t_;
};

class Rotated final : public Shape {
 public:
  Rotated(ShapePtr s, Vec3 axis, double angle) : s_(std::move(s)) {
    const Vec3 k = normalized(axis);
    const double c = std::cos(angle), si = std::sin(angle), t = 1 - c;
    r_[0] = {t * k.x * k.x + c, t * k.x * k.y - si * k.z, t * k.x * k.z + si * k.y};
    r_[1] = {t * k.x * k.y + si * k.z, t * k.y * k.y + c, t * k.y * k.z - si * k.x};
    r_[2] = {t * k.x * k.z - si * k.y, t * k.y * k.z + si * k.x, t * k.z * k.z + c};
  }
  int dimension() const override { return s_->dimension(); }
  double signed_distance(Vec3 p) const override { return s_->signed_distance(inv(p)); }
  double signed_distance_bounded(Vec3 p, double limit) const override {
    return s_->signed_distance_bounded(inv(p), limit);
  }
  Vec3 normal(Vec3 p) const override { return fwd(s_->normal(inv(p))); }
  bool inside(Vec3 p) const override { return s_->inside(inv(p)); }
  Aabb bounds() const override {
    return transformed_bounds(s_->bounds(), dimension(), [&](Vec3 v) { return fwd(v); });
  }
  std::optional<double> exact_volume() const override { return s_->exact_volume(); }
  std::optional<double> exact_area() const override { return s_->exact_area(); }

 private:
  Vec3 fwd(Vec3 v) const { return {dot(r_[0], v), dot(r_[1], v), dot(r_[2], v)}; }
  Vec3 inv(Vec3 v) const {
    return {r_[0].x * v.x + r_[1].x * v.y + r_[2].x * v.z,
            r_[0].y * v.x + r_[1].y * v.y + r_[2].y * v.z,
            r_[0].z * v.x + r_[1].z * v.y + r_[2].z * v.z};
  }
  ShapePtr s_;
  Vec3 r_[3];
};

class Scaled final : public Shape {
 public:
  Scaled(ShapePtr s, Vec3 f) : s_(std::move(s)), f_(f) {
    if (s_->dimension() == 2) f_.z = 1;
    min_ = std::min(f_.x, std::min(f_.y, f_.z));
  }
  int dimension() const override { return s_->dimension(); }
  double signed_distance(Vec3 p) const override { return min_ * s_->signed_distance(inv(p)); }
  double signed_distance_bounded(Vec3 p, double limit) const override {
    return min_ * s_->signed_distance_bounded(inv(p), limit / min_);
  }
  Vec3 normal(Vec3 p) const override {
    const Vec3 n = s_->normal(inv(p));
    return normalized({n.x / f_.x, n.y / f_.y, n.z / f_.z});
  }
  bool inside(Vec3 p) const override { return s_->inside(inv(p)); }
  Aabb bounds() const override {
    const Aabb b = s_->bounds();
    return transformed_bounds(b, dimension(), [&](Vec3 v) {
      return Vec3{v.x * f_.x, v.y * f_.y, v.z * f_.z};
    });
  }
  std::optional<double> exact_volume() const override {
    const auto v = s_->exact_volume();
    if (!v) return v;
    return *v * f_.x * f_.y * f_.z;
  }
  /// Uniform scaling only: s^(d-1) times the child's.
  std::optional<double> exact_area() const override {
    const auto a = s_->exact_area();
    const bool uniform = f_.x == f_.y && (dimension() == 2 || f_.y == f_.z);
    if (!a || !uniform) return std::nullopt;
    return dimension() == 2 ? *a * f_.x : *a * f_.x * f_.x;
  }

 private:
  Vec3 inv(Vec3 p) const { return {p.x / f_.x, p.y / f_.y, p.z / f_.z}; }
  ShapePtr s_;
  Vec3 f_;
  double min_ = 1;
};

enum class Op { kUnion, kIntersection, kDifference };

/// CSG node: union = min, intersection = max, difference = max(a, -b_1, -b_2, ...). The normal is
/// that of the child whose distance was selected.
class Csg final : public Shape {
 public:
  Csg(Op op, std::vector<ShapePtr> c) : op_(op), c_(std::move(c)) {
    box_ = c_[0]->bounds();
    if (op_ == Op::kUnion) {
      for (const auto& s : c_) box_.add(s->bounds());
    } else if (op_ == Op::kIntersection) {
      for (const auto& s : c_) box_ = intersect(box_, s->bounds());
    }
    for (const auto& s : c_) child_box_.push_back(s->bounds());
  }
  int dimension() const override { return c_[0]->dimension(); }
  double signed_distance(Vec3 p) const override { return eval(p, kNoLimit).first; }
  double signed_distance_bounded(Vec3 p, double limit) const override {
    return eval(p, limit).first;
  }
  Vec3 normal(Vec3 p) const override {
    const auto [d, k] = eval(p, kNoLimit);
    const Vec3 n = c_[k]->normal(p);
    return (op_ == Op::kDifference && k > 0) ? -n : n;
  }
  Aabb bounds() const override { return box_; }

 private:
  /// (distance, index of the selected child).
  static constexpr double kNoLimit = std::numeric_limits<double>::infinity();
  std::pair<double, std::size_t> eval(Vec3 p, double limit) const {
    if (dimension() == 2) p.z = 0;
    double best = 0;
    std::size_t arg = 0;
    for (std::size_t k = 0; k < c_.size(); ++k) {
      if (op_ == Op::kUnion) {
        // A child whose box is farther than the current (positive) best cannot be nearer.
        if (k > 0 && best > 0 && child_box_[k].distance2(p) >= best * best) continue;
        const double d = c_[k]->signed_distance_bounded(p, limit);
        if (k == 0 || d < best) best = d, arg = k;
      } else {
        const double d = (op_ == Op::kDifference && k > 0) ? -c_[k]->signed_distance(p)
                                                           : c_[k]->signed_distance(p);
        if (k == 0 || d > best) best = d, arg = k;
      }
    }
    return {best, arg};
  }
  Op op_;
  std::vector<ShapePtr> c_;
  std::vector<Aabb> child_box_;
  Aabb box_;
};

void check_children(const std::vector<ShapePtr>& c, const std::string& what) {
  if (c.empty()) throw InvalidArgument(what + " of nothing: give at least one shape");
  for (std::size_t k = 0; k < c.size(); ++k) {
    if (!c[k]) throw InvalidArgument(what + ": shape " + std::to_string(k) + " is null");
    if (c[k]->dimension() != c[0]->dimension()) {
      throw InvalidArgument(what + ": shape " + std::to_string(k) + " has dimension " +
                            std::to_string(c[k]->dimension()) + ", shape 0 has " +
                            std::to_string(c[0]->dimension()));
    }
  }
}

void check_shape(const ShapePtr& s, const std::string& what) {
  if (!s) throw InvalidArgument(what + ": the shape is null");
}

}  // namespace

ShapePtr translate(ShapePtr s, Vec3 offset) {
  check_shape(s, "translate");
  require_finite(offset, "translate.offset");
  if (s->dimension() == 2) offset.z = 0;
  return std::make_shared<Translated>(std::move(s), offset);
}

ShapePtr rotate(ShapePtr s, Vec3 axis, double angle) {
  check_shape(s, "rotate");
  require_finite(axis, "rotate.axis");
  require_positive(norm(axis), "rotate.axis length");
  if (!std::isfinite(angle)) throw InvalidArgument("rotate.angle must be finite");
  if (s->dimension() == 2 && (axis.x != 0 || axis.y != 0)) {
    throw InvalidArgument("rotate: a 2D shape rotates about z only; axis must be (0, 0, +-1)");
  }
  return std::make_shared<Rotated>(std::move(s), axis, angle);
}

ShapePtr scale(ShapePtr s, Vec3 factors) {
  check_shape(s, "scale");
  require_positive(factors.x, "scale.x");
  require_positive(factors.y, "scale.y");
  if (s->dimension() == 3) require_positive(factors.z, "scale.z");
  return std::make_shared<Scaled>(std::move(s), factors);
}

ShapePtr csg_union(std::vector<ShapePtr> children) {
  check_children(children, "union");
  if (children.size() == 1) return children[0];
  return std::make_shared<Csg>(Op::kUnion, std::move(children));
}

ShapePtr csg_intersection(std::vector<ShapePtr> children) {
  check_children(children, "intersection");
  if (children.size() == 1) return children[0];
  return std::make_shared<Csg>(Op::kIntersection, std::move(children));
}

ShapePtr csg_difference(ShapePtr a, std::vector<ShapePtr> b) {
  b.insert(b.begin(), std::move(a));
  check_children(b, "difference");
  if (b.size() == 1) return b[0];
  return std::make_shared<Csg>(Op::kDifference, std::move(b));
}

}  // namespace sadr::geometry
