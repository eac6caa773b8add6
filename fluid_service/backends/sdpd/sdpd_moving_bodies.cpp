// SPDX-License-Identifier: MIT
/// \file sdpd_moving_bodies.cpp
/// Bodies whose wall particles move (FluidModel::moving_bodies; docs/fluid-core.md "Moving
/// walls"): every wall particle of such a body is placed by its body's rigid motion
/// (common/rigid_motion.hpp) from its initial position and the time, x(t) and v(t) in closed form,
/// at every state the integrator evaluates (the predictor's at t + dt, the corrector's at t + dt)
/// and after a restore. Nothing is integrated, so the placement at a time is the same bits
/// whenever it is made (bit-identical restarts need only the saved time). With the placement go
/// what rides on the body: the normals of its geometry surfaces (Adami walls,
/// FluidModel::wall_tangents) turn with it, and the torque reference of a body force group whose
/// wall particles belong to it moves with it.
#include <cmath>
#include <string>

#include "sadr/common/status.hpp"
#include "sdpd_backend.hpp"

namespace sadr::fluid {

namespace {
/// x into [lo, hi) on the periodic axes (a body may have travelled many box lengths).
void wrap_far(const Box& box, const PeriodicBox& pbox, double* x) {
  for (int a = 0; a < box.dimension; ++a) {
    if (!box.periodic[a]) continue;
    const double len = box.hi[a] - box.lo[a];
    x[a] -= len * std::floor((x[a] - box.lo[a]) / len);
  }
  pbox.wrap(x);  // (round-off may leave x at hi)
}
}  // namespace

void SdpdBackend::setup_moving_bodies() {
  moving_ = {};
  const std::size_t n = mass_.size();
  moving_.of.assign(model_.moving_bodies.empty() ? 0 : n, -1);
  for (std::size_t b = 0; b < model_.moving_bodies.size(); ++b) {
    const MovingBody& body = model_.moving_bodies[b];
    std::size_t walls = 0;
    for (const std::uint32_t p : body.particles) {
      if (p >= n) {
        throw InvalidArgument("sdpd: moving_bodies '" + body.name + "': particle " +
                              std::to_string(p) + " out of range [0, " + std::to_string(n) + ")");
      }
      if (!wall_[p]) continue;
      if (moving_.of[p] >= 0) {
        throw InvalidArgument("sdpd: moving_bodies '" + body.name + "': wall particle " +
                              std::to_string(p) + " belongs to two moving bodies");
      }
      moving_.of[p] = static_cast<std::int32_t>(moving_.particle.size());
      moving_.particle.push_back(p);
      moving_.body.push_back(static_cast<std::uint32_t>(b));
      moving_.x0.insert(moving_.x0.end(), &y_.x[3 * p], &y_.x[3 * p] + 3);
      ++walls;
    }
    if (walls == 0) {
      throw InvalidArgument("sdpd: moving_bodies '" + body.name +
                            "' holds no wall particle (allowed: a solid body's wall particles)");
    }
  }
  if (moving_.particle.empty()) return;
  // Geometry surfaces (Adami walls) of the moving particles: their normals turn with the body.
  const WallTangents& t = model_.wall_tangents;
  for (std::size_t k = 0; k < t.particles.size(); ++k) {
    const std::uint32_t p = t.particles[k];
    if (p >= n || moving_.of[p] < 0) continue;
    moving_.tangent.push_back(static_cast<std::uint32_t>(k));
    moving_.tangent_body.push_back(moving_.body[static_cast<std::size_t>(moving_.of[p])]);
    moving_.n0.insert(moving_.n0.end(), &t.normals[3 * k], &t.normals[3 * k] + 3);
  }
  // Body force groups: the torque reference follows the body of the group's first wall particle.
  bodies_.moving.assign(bodies_.walls.size(), -1);
  bodies_.reference0 = bodies_.reference;
  for (std::size_t g = 0; g < bodies_.walls.size(); ++g) {
    const std::int32_t k = moving_.of[bodies_.walls[g].front()];
    if (k >= 0) {
      bodies_.moving[g] = static_cast<std::int32_t>(moving_.body[static_cast<std::size_t>(k)]);
    }
  }
  move_bodies(y_, 0.0);
}

void SdpdBackend::move_bodies(Y& y, double t) {
  if (moving_.particle.empty()) return;
  const int dim = model_.box.dimension;
  for (std::size_t k = 0; k < moving_.particle.size(); ++k) {
    const std::size_t p = moving_.particle[k];
    const RigidMotion& m = model_.moving_bodies[moving_.body[k]].motion;
    const std::array<double, 3> x = m.position(&moving_.x0[3 * k], t);
    const std::array<double, 3> v = m.velocity_of(&moving_.x0[3 * k], t);
    for (int a = 0; a < 3; ++a) {
      y.x[3 * p + a] = a < dim ? x[a] : 0.0;
      y.v[3 * p + a] = a < dim ? v[a] : 0.0;
    }
    wrap_far(model_.box, pbox_, &y.x[3 * p]);
    if (!pbox_.inside(&y.x[3 * p])) {
      throw NumericalFailure("sdpd: moving body '" + model_.moving_bodies[moving_.body[k]].name +
                             "' reaches beyond the box on a walled axis at t = " + format_value(t) +
                             " (wall particle " + std::to_string(p) +
                             "); allowed: a motion that keeps the body inside the box");
    }
  }
  WallTangents& tg = model_.wall_tangents;
  for (std::size_t k = 0; k < moving_.tangent.size(); ++k) {
    const RigidMotion& m = model_.moving_bodies[moving_.tangent_body[k]].motion;
    const std::array<double, 3> nr = m.rotate(&moving_.n0[3 * k], t);
    for (int a = 0; a < 3; ++a) tg.normals[3 * moving_.tangent[k] + a] = a < dim ? nr[a] : 0.0;
  }
  for (std::size_t g = 0; g < bodies_.moving.size(); ++g) {
    if (bodies_.moving[g] < 0) continue;
    const RigidMotion& m = model_.moving_bodies[static_cast<std::size_t>(bodies_.moving[g])].motion;
    std::array<double, 3> c = m.position(bodies_.reference0[g].data(), t);
    for (int a = dim; a < 3; ++a) c[a] = 0.0;
    wrap_far(model_.box, pbox_, c.data());
    bodies_.reference[g] = c;
  }
  moving_.time = t;
}

std::array<double, 3> SdpdBackend::moving_acceleration(std::size_t w) const {
  if (moving_.of.empty() || moving_.of[w] < 0) return {0.0, 0.0, 0.0};
  const auto k = static_cast<std::size_t>(moving_.of[w]);
  return model_.moving_bodies[moving_.body[k]].motion.acceleration_of(&moving_.x0[3 * k],
                                                                      moving_.time);
}

}  // namespace sadr::fluid
