// SPDX-License-Identifier: MIT
/// \file scene_wall_tangents.hpp
/// Morris walls made by a scene's `geometry` section: the tangent plane of every wall particle
/// (common/wall_surface.hpp WallTangents), sent to both services and used by the health check.
#pragma once

#include "sadr/common/wall_surface.hpp"
#include "sadr/orchestrator/scene.hpp"

namespace sadr::orchestrator {

/// With fluid.wall_model morris, particles made by a geometry section and no fluid.wall_planes:
/// every wall particle j with its depth behind its surface and its inward unit normal
/// (GeometryReport::surface_distance, surface_normal), i.e. the tangent plane at its closest
/// surface point. Else empty.
[[nodiscard]] WallTangents scene_wall_tangents(const Scene& scene);

}  // namespace sadr::orchestrator
