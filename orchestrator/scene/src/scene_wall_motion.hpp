// SPDX-License-Identifier: MIT
/// \file scene_wall_motion.hpp
/// (private) Prescribed wall velocities (docs/scene-format.md "Moving walls"): a wall fill rule's
/// `velocity` and a solid body's `motion`. A motion is a rigid-body velocity field
/// v(x) = velocity + angular_velocity axis x (x - center); the loader evaluates it at every wall
/// particle of the body, whose position stays fixed, and the particle carries that velocity as
/// its own (the fluid backend holds it and its wall model uses it). The motion must be tangential
/// to the wall's surface: a component along the surface normal is refused where the normal is
/// known (geometry bodies; a wall fill rule that lies wholly beyond the fluid along a walled axis).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "sadr/common/rigid_motion.hpp"
#include "scene_parts.hpp"

namespace sadr::orchestrator::detail {

struct WallMotion {
  std::array<double, 3> velocity{};     ///< translation [length/time]
  double angular_velocity = 0.0;        ///< [1/time], about `axis` through `center`
  std::array<double, 3> center{};       ///< [length]
  std::array<double, 3> axis{0, 0, 1};  ///< unit
  /// `moves: true`: the body's wall particles follow the motion (their positions move; the
  /// fluid backend places them, docs/fluid-core.md "Moving walls"); false: they stay in place.
  bool moves = false;

  /// The velocity of the rigid-body motion at x (3 doubles).
  [[nodiscard]] std::array<double, 3> at(const double* x) const;
  /// The motion as the fluid backend takes it (moving bodies).
  [[nodiscard]] RigidMotion rigid() const { return {velocity, angular_velocity, center, axis}; }
};

/// The `motion` map of `parent` (absent: nullopt): {velocity: [..]} and/or
/// {angular_velocity: w, center: [..], axis: [..] (3D only)}, and `moves` (a solid body's walls
/// follow the motion; refused with Morris walls). Errors are reported.
std::optional<WallMotion> read_wall_motion(SceneContext& ctx, const Field& parent);

/// Whether the scene's fluid backend holds a prescribed wall velocity (an unknown one: true, it
/// is reported elsewhere).
bool backend_moves_walls(const SceneContext& ctx);

/// Refuses (at `where`) a moving wall when the scene's fluid backend keeps walls at rest.
void require_moving_walls(SceneContext& ctx, const Field& where);

/// Lattice fill rules: wall particles `members` of a rule whose velocity is `v`; refuses a
/// velocity component along a walled axis on which every member lies beyond every fluid particle
/// (a box-face wall moving into or away from the fluid), at `where`.
void check_face_wall_motion(SceneContext& ctx, const Field& where, const std::array<double, 3>& v,
                            const std::vector<std::uint32_t>& members);

/// Geometry: the velocity of each of a body's wall particles `members` from `motion`, set in the
/// scene's particles, refusing (at `where`) one with a component along its surface normal
/// `normals[i]` (unit, per particle) larger than 1e-6 of the largest speed, unless the body
/// moves (`moves`), whose walls follow the motion.
void apply_body_motion(SceneContext& ctx, const Field& where, const WallMotion& motion,
                       const std::vector<std::uint32_t>& members,
                       const std::vector<std::array<double, 3>>& normals);

}  // namespace sadr::orchestrator::detail
