// SPDX-License-Identifier: MIT
// Bounding-volume hierarchy over triangles (3D) or segments (2D) with the per-node dipole data of
// Barill et al. (2018) for the far-field winding number (first order: the dipole) (private header
// of mesh_shape.cpp).
#pragma once

#include <array>
#include <limits>
#include <vector>

#include "sadr/geometry/vec.hpp"

namespace sadr::geometry {

/// One element: a triangle (v[0..2]) or a segment (v[0..1]).
using Element = std::array<Vec3, 3>;

class Bvh {
 public:
  Bvh(int dimension, std::vector<Element> elements, int leaf_size);

  /// Winding number; nodes with |p - centre| > beta * radius count as one dipole (beta = 0:
  /// every element exactly).
  [[nodiscard]] double winding(Vec3 p, double beta) const;
  struct Hit {
    Vec3 point;
    double distance2 = 0;
    int element = -1;  ///< index in the input order
  };
  /// Nearest element closer than sqrt(max_distance2); element = -1 if there is none.
  [[nodiscard]] Hit closest(Vec3 p,
                            double max_distance2 = std::numeric_limits<double>::infinity()) const;
  /// Unit normal of element i (input order): right-hand rule in 3D, (dy, -dx) in 2D.
  [[nodiscard]] Vec3 element_normal(int i) const;

 private:
  struct Node {
    Aabb box;
    Vec3 center;    ///< area-weighted centroid of its elements
    Vec3 area_vec;  ///< sum of area-weighted normals (the dipole moment)
    double radius = 0;
    int begin = 0, end = 0;     ///< element range in elems_
    int left = -1, right = -1;  ///< children (-1: leaf)
  };
  int build(int begin, int end);
  double element_winding(const Element& e, Vec3 p) const;
  Vec3 element_closest(const Element& e, Vec3 p) const;
  double winding_node(int n, Vec3 p, double beta) const;

  int dim_;
  int leaf_size_;
  std::vector<Element> elems_;  ///< reordered
  std::vector<int> order_;      ///< elems_[k] is input element order_[k]
  std::vector<Vec3> centroid_, area_vec_;
  std::vector<Node> nodes_;
};

}  // namespace sadr::geometry
