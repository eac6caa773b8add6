// SPDX-License-Identifier: MIT
/// \file rigid_motion.hpp
/// The rigid motion of a body whose wall particles move (docs/fluid-core.md "Moving walls"): the
/// one home of its closed form, used by the scene loader, the SDPD backend and the tests.
///
/// A point at x0 at t = 0 is at x(t) = x0 + V t + (R(theta) - I)(x0 - c0) with theta = omega t,
/// R the rotation by theta about the unit `axis` (Rodrigues; in 2D the axis is z), c0 `center`;
/// the centre moves to c(t) = c0 + V t. Its velocity is the rigid-body field
/// v = V + omega axis x R(theta)(x0 - c0), its acceleration the centripetal
/// a = -omega^2 (R(theta)(x0 - c0))_perp (the part normal to the axis). Evaluated from t directly
/// (nothing is integrated), so the same t gives the same bits; at t = 0 x(0) = x0 exactly.
#pragma once

#include <array>
#include <cmath>

namespace sadr {

struct RigidMotion {
  std::array<double, 3> velocity{};     ///< V [length/time]
  double angular_velocity = 0.0;        ///< omega [1/time], about `axis` through `center`
  std::array<double, 3> center{};       ///< c0 at t = 0 [length]
  std::array<double, 3> axis{0, 0, 1};  ///< unit

  /// R(omega t) r for r (3 doubles).
  [[nodiscard]] std::array<double, 3> rotate(const double* r, double t) const {
    if (angular_velocity == 0.0) return {r[0], r[1], r[2]};
    const double th = angular_velocity * t, c = std::cos(th), s = std::sin(th);
    const auto& k = axis;
    const double kr = k[0] * r[0] + k[1] * r[1] + k[2] * r[2];
    const std::array<double, 3> kxr{k[1] * r[2] - k[2] * r[1], k[2] * r[0] - k[0] * r[2],
                                    k[0] * r[1] - k[1] * r[0]};
    std::array<double, 3> out{};
    for (int a = 0; a < 3; ++a) out[a] = r[a] * c + kxr[a] * s + k[a] * kr * (1.0 - c);
    return out;
  }
  /// R(omega t)(x0 - c0): the arm of the point at x0 at time t.
  [[nodiscard]] std::array<double, 3> arm(const double* x0, double t) const {
    const double r[3] = {x0[0] - center[0], x0[1] - center[1], x0[2] - center[2]};
    return rotate(r, t);
  }
  /// x(t) of the point at x0 at t = 0 (unwrapped).
  [[nodiscard]] std::array<double, 3> position(const double* x0, double t) const {
    const std::array<double, 3> q = arm(x0, t);
    std::array<double, 3> out{};
    for (int a = 0; a < 3; ++a) {
      const double r = x0[a] - center[a];
      out[a] = x0[a] + velocity[a] * t + (q[a] - r);
    }
    return out;
  }
  /// The velocity at time t of the point at x0 at t = 0.
  [[nodiscard]] std::array<double, 3> velocity_of(const double* x0, double t) const {
    const std::array<double, 3> q = arm(x0, t);
    const double w = angular_velocity;
    const auto& k = axis;
    return {velocity[0] + w * (k[1] * q[2] - k[2] * q[1]),
            velocity[1] + w * (k[2] * q[0] - k[0] * q[2]),
            velocity[2] + w * (k[0] * q[1] - k[1] * q[0])};
  }
  /// The acceleration at time t of the point at x0 at t = 0 (centripetal).
  [[nodiscard]] std::array<double, 3> acceleration_of(const double* x0, double t) const {
    if (angular_velocity == 0.0) return {0.0, 0.0, 0.0};
    const std::array<double, 3> q = arm(x0, t);
    const double kq = axis[0] * q[0] + axis[1] * q[1] + axis[2] * q[2];
    const double w2 = angular_velocity * angular_velocity;
    return {-w2 * (q[0] - kq * axis[0]), -w2 * (q[1] - kq * axis[1]), -w2 * (q[2] - kq * axis[2])};
  }
};

}  // namespace sadr
