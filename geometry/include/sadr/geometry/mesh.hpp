// SPDX-License-Identifier: MIT
/// \file mesh.hpp
/// Triangle surface meshes (3D) and segment polylines (2D) as shapes: inside by the generalized
/// winding number (Jacobson, Kavan & Sorkine-Hornung 2013) with the far-field dipole
/// approximation of Barill et al. (2018) over a bounding-volume hierarchy; unsigned distance,
/// closest point and normal from the same hierarchy; sign from the winding number. Watertightness
/// is not required: away from a hole the winding number stays close to 1 inside and 0 outside.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "sadr/geometry/shape.hpp"

namespace sadr::geometry {

/// A surface: triangles in 3D, segments in 2D (z = 0), indexing `vertices`.
struct SurfaceMesh {
  int dimension = 3;
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> triangles;  ///< dimension 3
  std::vector<std::array<int, 2>> segments;   ///< dimension 2
  std::string source;                         ///< file (and group) for error messages

  [[nodiscard]] std::size_t size() const {
    return dimension == 3 ? triangles.size() : segments.size();
  }
};

/// Throws InvalidArgument naming mesh.source (and the vertex or element) on an empty mesh,
/// non-finite vertices or indices out of range.
void validate(const SurfaceMesh& mesh);

struct MeshShapeOptions {
  /// Far-field threshold: a BVH node whose dipole centre is farther than beta times its radius
  /// counts as one dipole. 0 = exact winding number (sum over every element, O(n) per query).
  double far_field_beta = 2.0;
  /// Elements per BVH leaf.
  int leaf_size = 8;
};

class Bvh;

/// A closed (or nearly closed) surface as a Shape. Orientation is fixed at construction: a
/// surface whose enclosed signed volume is negative (inverted normals) is flipped, and
/// was_inverted() says so.
class MeshShape final : public Shape {
 public:
  explicit MeshShape(SurfaceMesh mesh, MeshShapeOptions options = {});
  ~MeshShape() override;
  MeshShape(const MeshShape&) = delete;
  MeshShape& operator=(const MeshShape&) = delete;

  int dimension() const override { return mesh_.dimension; }
  double signed_distance(Vec3 p) const override;
  /// Searches the BVH only within `limit`: far from the surface it costs the winding number only.
  double signed_distance_bounded(Vec3 p, double limit) const override;
  Vec3 normal(Vec3 p) const override;
  /// winding_number(p) > 0.5.
  bool inside(Vec3 p) const override;
  Aabb bounds() const override { return box_; }
  /// The sum of the triangle areas (3D) or segment lengths (2D).
  std::optional<double> exact_area() const override;

  /// Generalized winding number at p (1 inside a closed outward surface, 0 outside).
  [[nodiscard]] double winding_number(Vec3 p) const;
  /// The same summed exactly over every element (reference; O(n)).
  [[nodiscard]] double winding_number_exact(Vec3 p) const;
  struct Closest {
    Vec3 point;
    double distance = 0;
    int element = -1;
  };
  /// Nearest surface point to p.
  [[nodiscard]] Closest closest(Vec3 p) const;
  /// Volume (area in 2D) enclosed, by the divergence theorem (exact for a closed mesh).
  [[nodiscard]] double enclosed_volume() const { return volume_; }
  [[nodiscard]] bool was_inverted() const { return inverted_; }
  [[nodiscard]] const SurfaceMesh& mesh() const { return mesh_; }

 private:
  SurfaceMesh mesh_;
  MeshShapeOptions opt_;
  std::unique_ptr<Bvh> bvh_;
  Aabb box_;
  double volume_ = 0;
  bool inverted_ = false;
};

/// validate(mesh), then a MeshShape.
std::shared_ptr<const MeshShape> make_mesh_shape(SurfaceMesh mesh, MeshShapeOptions options = {});

}  // namespace sadr::geometry
