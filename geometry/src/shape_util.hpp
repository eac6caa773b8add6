// SPDX-License-Identifier: MIT
// Argument checks and small helpers shared by the shape sources (private header).
#pragma once

#include <cmath>
#include <string>

#include "sadr/common/status.hpp"
#include "sadr/geometry/vec.hpp"

namespace sadr::geometry {

inline void require_dimension(int dimension, const std::string& what) {
  if (dimension != 2 && dimension != 3) {
    throw InvalidArgument(what + ": dimension must be 2 or 3, got " + std::to_string(dimension));
  }
}
inline void require_finite(Vec3 v, const std::string& what) {
  if (!all_finite(v)) {
    throw InvalidArgument(what + " must be finite, got (" + format_value(v.x) + ", " +
                          format_value(v.y) + ", " + format_value(v.z) + ")");
  }
}
inline void require_positive(double v, const std::string& what) {
  if (!(v > 0) || !std::isfinite(v)) {
    throw InvalidArgument(what + " must be finite and > 0, got " + format_value(v));
  }
}
/// A unit vector perpendicular to v (v != 0), or x if v == 0.
inline Vec3 any_perpendicular(Vec3 v) {
  if (norm2(v) == 0) return {1, 0, 0};
  const Vec3 t = std::abs(v.x) < 0.9 * norm(v) ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  return normalized(cross(v, t));
}

}  // namespace sadr::geometry
