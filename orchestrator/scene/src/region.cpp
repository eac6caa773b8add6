// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/region.hpp"

#include <algorithm>
#include <cmath>

namespace sadr::orchestrator {

std::string_view to_string(RegionShape shape) {
  switch (shape) {
    case RegionShape::kAll:
      return "all";
    case RegionShape::kBox:
      return "box";
    case RegionShape::kSphere:
      return "sphere";
    case RegionShape::kAnnulus:
      return "annulus";
    case RegionShape::kChannel:
      return "channel";
    case RegionShape::kIds:
      return "ids";
  }
  return "unknown";
}

bool Region::contains(const std::array<double, 3>& x, int dimension, double tol) const {
  switch (shape) {
    case RegionShape::kAll:
      return true;
    case RegionShape::kBox:
      for (int a = 0; a < dimension; ++a) {
        if (x[a] < lower[a] - tol || x[a] > upper[a] + tol) return false;
      }
      return true;
    case RegionShape::kSphere:
    case RegionShape::kAnnulus: {
      double r2 = 0.0;
      for (int a = 0; a < dimension; ++a) r2 += (x[a] - center[a]) * (x[a] - center[a]);
      const double r = std::sqrt(r2);
      if (r > radius + tol) return false;
      return shape == RegionShape::kSphere || r >= inner_radius - tol;
    }
    case RegionShape::kChannel:
      return x[axis] >= axis_lower - tol && x[axis] <= axis_upper + tol;
    case RegionShape::kIds:
      return false;
  }
  return false;
}

void resolve_membership(Region& region, const ParticleState& particles, double tol) {
  region.particles.clear();
  auto kind_ok = [&](std::size_t i) {
    return region.kinds.empty() || std::find(region.kinds.begin(), region.kinds.end(),
                                             particles.kind(i)) != region.kinds.end();
  };
  if (region.shape == RegionShape::kIds) {
    for (const std::uint32_t i : region.ids) {
      if (i < particles.size() && kind_ok(i)) region.particles.push_back(i);
    }
    return;
  }
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (!kind_ok(i)) continue;
    const std::array<double, 3> x{particles.positions[3 * i], particles.positions[3 * i + 1],
                                  particles.positions[3 * i + 2]};
    if (region.contains(x, particles.dimension, tol)) {
      region.particles.push_back(static_cast<std::uint32_t>(i));
    }
  }
}

}  // namespace sadr::orchestrator
