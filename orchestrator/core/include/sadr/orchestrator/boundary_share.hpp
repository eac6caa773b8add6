// SPDX-License-Identifier: MIT
/// \file boundary_share.hpp
/// Where a boundary flux (scene `boundary_fluxes`) enters: the first layer of fluid particles at
/// a box face and each one's share A_i of the face's area (docs/method.md 4d).
#pragma once

#include <cstdint>
#include <vector>

#include "sadr/common/particle_state.hpp"
#include "sadr/orchestrator/region.hpp"

namespace sadr::orchestrator {

struct BoundaryShare {
  std::vector<std::uint32_t> particles;  ///< the first fluid layer at the face, ascending
  std::vector<double> areas;             ///< A_i [length^(d-1)], parallel to particles
  double area = 0;                       ///< A: the face's area inside the region
};

/// The face is axis `axis`'s lower (`upper` false) or upper box face; `extent` (a box or channel
/// region, or nullptr) restricts it along the other axes: A = prod_t |[lo_t, hi_t] of the box
/// and the region| (1 in 1D). Candidates are the fluid particles whose tangential coordinates
/// lie on that patch (within `tol`); the first layer is those within l_i / 2 (l_i = V_i^(1/d))
/// of the outermost candidate along the normal. A_i = A l_i^(d-1) / sum_j l_j^(d-1), so
/// sum_i A_i = A to round-off (checked to 1e-12 A). Throws InvalidArgument for an empty patch
/// or no fluid particle on it.
[[nodiscard]] BoundaryShare boundary_share(const ParticleState& particles, const Box& box, int axis,
                                           bool upper, const Region* extent, double tol);

}  // namespace sadr::orchestrator
