// SPDX-License-Identifier: MIT
/// \file shape.hpp
/// Shapes in 2D and 3D behind one interface: signed distance, outward normal, inside test and
/// bounding box; primitives, transforms and CSG to any depth (docs/geometry.md).
///
/// Distance contract. signed_distance(p) is negative inside, positive outside, and its sign is
/// exact. Its magnitude never exceeds the Euclidean distance from p to the surface, and equals it
/// for every primitive here (box, sphere/disk, ellipsoid/ellipse, cylinder, capsule, torus,
/// polygon, extrusion) and for rigid transforms and uniform scaling of them. CSG operations and
/// non-uniform scaling keep the sign exact and the magnitude a lower bound (exact outside a union
/// and inside an intersection where one child is nearest). Consumers that cull by distance
/// (particles.hpp) rely only on this lower bound.
///
/// 2D shapes live in the z = 0 plane; their queries ignore z. Volumes are areas in 2D.
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "sadr/geometry/vec.hpp"

namespace sadr::geometry {

class Shape {
 public:
  virtual ~Shape() = default;
  /// 2 or 3.
  [[nodiscard]] virtual int dimension() const = 0;
  /// Signed distance [length], negative inside (see the contract above).
  [[nodiscard]] virtual double signed_distance(Vec3 p) const = 0;
  /// The signed distance where its magnitude is at most `limit`; elsewhere any value of the right
  /// sign and magnitude above `limit` (and not above the true distance). Lets meshes and CSG skip
  /// work far from the surface; the default is signed_distance.
  [[nodiscard]] virtual double signed_distance_bounded(Vec3 p, double limit) const {
    (void)limit;
    return signed_distance(p);
  }
  /// Outward unit normal of the nearest surface point (the gradient of the distance). The default
  /// takes central differences of signed_distance with a step 1e-6 of the bounding box size.
  [[nodiscard]] virtual Vec3 normal(Vec3 p) const;
  /// True strictly inside (signed_distance < 0).
  [[nodiscard]] virtual bool inside(Vec3 p) const { return signed_distance(p) < 0; }
  /// A box containing the shape (may be loose for CSG).
  [[nodiscard]] virtual Aabb bounds() const = 0;
  /// Exact volume (area in 2D) where a closed formula exists; nullopt otherwise (CSG, meshes).
  [[nodiscard]] virtual std::optional<double> exact_volume() const { return std::nullopt; }
  /// Area of the surface (its perimeter in 2D) where a closed formula or a quadrature to round-off
  /// exists: every primitive (the ellipse's perimeter and the ellipsoid's area by quadrature),
  /// their rigid transforms and uniform scaling; the element sum for meshes; nullopt otherwise
  /// (CSG, non-uniform scaling).
  [[nodiscard]] virtual std::optional<double> exact_area() const { return std::nullopt; }
};

using ShapePtr = std::shared_ptr<const Shape>;

// ---- primitives (all throw InvalidArgument naming the parameter on a bad size) ----
/// Axis-aligned box [lo, hi]; dimension 2 uses x, y only.
ShapePtr make_box(Vec3 lo, Vec3 hi, int dimension = 3);
/// Sphere (dimension 3) or disk (dimension 2).
ShapePtr make_sphere(Vec3 center, double radius, int dimension = 3);
/// Axis-aligned ellipsoid (3) / ellipse (2) with semi-axes `radii`; exact distance (Eberly's
/// bisection on the closest-point equation, to machine precision).
ShapePtr make_ellipsoid(Vec3 center, Vec3 radii, int dimension = 3);
/// Solid cylinder of `radius` between the centres of its two end caps a and b.
ShapePtr make_cylinder(Vec3 a, Vec3 b, double radius);
/// Capsule: all points within `radius` of segment ab (3D; dimension 2 gives a stadium).
ShapePtr make_capsule(Vec3 a, Vec3 b, double radius, int dimension = 3);
/// Torus around the z axis through `center`: ring radius R (major), tube radius r (minor), r < R.
ShapePtr make_torus(Vec3 center, double major_radius, double minor_radius);
/// Simple polygon in the xy plane, either orientation; inside by the even-odd rule (a
/// self-intersecting outline is accepted and read that way).
ShapePtr make_polygon(std::vector<Vec3> vertices);
/// A 2D polygon extruded along z over [z0, z1].
ShapePtr make_extrusion(std::vector<Vec3> vertices, double z0, double z1);

// ---- transforms ----
ShapePtr translate(ShapePtr s, Vec3 offset);
/// Rotation by `angle` [rad] about `axis` through the origin (2D shapes: axis must be z).
ShapePtr rotate(ShapePtr s, Vec3 axis, double angle);
/// Scaling about the origin; factors > 0. Uniform factors keep the distance exact; otherwise the
/// distance is d(p / s) * min(s), a lower bound.
ShapePtr scale(ShapePtr s, Vec3 factors);

// ---- CSG (children of one dimension; throw InvalidArgument on none or mixed) ----
ShapePtr csg_union(std::vector<ShapePtr> children);
ShapePtr csg_intersection(std::vector<ShapePtr> children);
/// a minus every one of `b`.
ShapePtr csg_difference(ShapePtr a, std::vector<ShapePtr> b);

}  // namespace sadr::geometry
