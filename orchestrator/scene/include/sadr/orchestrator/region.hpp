// SPDX-License-Identifier: MIT
/// \file region.hpp
/// Named regions of a scene (box, sphere/disk, annulus, channel, id list)
/// and their resolution to particle indices (sadr.common.v1.RegionMembership).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "sadr/common/particle_state.hpp"

namespace sadr::orchestrator {

enum class RegionShape {
  kAll,      ///< the whole box (the built-in region "all")
  kBox,      ///< lower <= x <= upper on every active axis
  kSphere,   ///< |x - center| <= radius (a disk in 2D, an interval in 1D)
  kAnnulus,  ///< inner_radius <= |x - center| <= radius (a spherical shell in 3D)
  kChannel,  ///< lower <= x[axis] <= upper (a slab, unbounded along the other axes)
  kIds,      ///< an explicit list of particle ids (no geometry)
};
std::string_view to_string(RegionShape shape);

/// A region and the particles in it. Boundaries are inclusive within a
/// relative tolerance of 1e-9 of the box size, so lattice points that sit
/// exactly on a face are inside.
struct Region {
  std::string name;
  RegionShape shape = RegionShape::kAll;
  std::array<double, 3> lower{};         ///< box [length]
  std::array<double, 3> upper{};         ///< box [length]
  std::array<double, 3> center{};        ///< sphere, annulus [length]
  double radius = 0.0;                   ///< sphere, annulus outer radius [length]
  double inner_radius = 0.0;             ///< annulus [length]
  int axis = 0;                          ///< channel: normal axis 0, 1, 2
  double axis_lower = 0.0;               ///< channel [length]
  double axis_upper = 0.0;               ///< channel [length]
  std::vector<std::uint32_t> ids;        ///< kIds: the listed particle ids, ascending
  std::vector<ParticleKind> kinds;       ///< only these kinds are members; empty = any
  std::vector<std::uint32_t> particles;  ///< resolved members, ascending indices

  /// True when point x (3 components, unused axes ignored) is inside the
  /// shape, with the absolute tolerance `tol` [length]. Ignores `kinds`.
  /// False for kIds (membership by id only).
  [[nodiscard]] bool contains(const std::array<double, 3>& x, int dimension, double tol) const;
};

/// Fills region.particles with the indices of the particles inside the shape
/// (kIds: the listed ids below particles.size()) whose kind is allowed.
/// @param tol absolute boundary tolerance [length]
void resolve_membership(Region& region, const ParticleState& particles, double tol);

}  // namespace sadr::orchestrator
