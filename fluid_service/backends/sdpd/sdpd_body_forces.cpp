// SPDX-License-Identifier: MIT
/// \file sdpd_body_forces.cpp
/// The force and torque the fluid exerts on bodies (FluidModel::body_forces; docs/fluid-core.md
/// "Forces on bodies"). A body is a set of wall particles. At every force evaluation of the
/// full-list gather, for each wall particle w of a body and each fluid neighbour f, the pair force
/// on f from w is evaluated as the gather does it (sdpd_gather.cpp gather_pairs: the pressure and
/// viscous terms of SdpdMomentumTerm, with the Morris extrapolated velocity or the Adami wall
/// pressure and velocity where those walls are on); the force on the body is minus its sum:
/// \f$ F = -\sum_{w} \sum_f f_{f \leftarrow w} \f$, the torque \f$ \sum_w (x_w - x_c) \times
/// (-\sum_f f_{f \leftarrow w}) \f$ about the centroid x_c of the body's wall particles.
/// Not included: the thermal noise of fluid-wall pairs (zero mean) and the transport-velocity
/// A-tensor term (sdpd_transport_velocity.cpp).
///
/// The step reports the trapezoidal mean over its sub-steps, sum dt (F(Y) + F(Y~)) / 2 over
/// the step's length: the impulse the integrator actually gave the fluid through the body's
/// wall particles, so that (change of the fluid's momentum) = (body force on the fluid) -
/// (this force) x (step length) to round-off when the fluid-fluid pair forces cancel (no
/// noise, no transport velocity, no open boundary).
#include <algorithm>
#include <array>
#include <string>

#include "sadr/common/status.hpp"
#include "sdpd_backend.hpp"

namespace sadr::fluid {

void SdpdBackend::setup_bodies() {
  bodies_ = {};
  const std::size_t n = mass_.size();
  for (const auto& group : model_.body_forces) {
    std::vector<std::uint32_t> walls;
    for (const std::uint32_t p : group.particles) {
      if (p >= n) {
        throw InvalidArgument("sdpd: body_forces '" + group.name + "': particle " +
                              std::to_string(p) + " out of range [0, " + std::to_string(n) + ")");
      }
      if (wall_[p]) walls.push_back(p);
    }
    std::sort(walls.begin(), walls.end());
    walls.erase(std::unique(walls.begin(), walls.end()), walls.end());
    if (walls.empty()) {
      throw InvalidArgument("sdpd: body_forces '" + group.name +
                            "' holds no wall particle (allowed: a solid body or a region of "
                            "wall particles)");
    }
    // centroid: minimum-image offsets from the first particle (a body may cross a periodic face)
    const double* x0 = &y_.x[3 * walls.front()];
    std::array<double, 3> c{};
    for (const std::uint32_t w : walls) {
      double d[3] = {y_.x[3 * w] - x0[0], y_.x[3 * w + 1] - x0[1], y_.x[3 * w + 2] - x0[2]};
      pbox_.minimum_image(d);
      for (int a = 0; a < 3; ++a) c[a] += d[a];
    }
    for (int a = 0; a < 3; ++a) c[a] = x0[a] + c[a] / static_cast<double>(walls.size());
    pbox_.wrap(c.data());
    for (int a = model_.box.dimension; a < 3; ++a) c[a] = 0.0;
    bodies_.walls.push_back(std::move(walls));
    bodies_.reference.push_back(c);
  }
  bodies_.sum.assign(6 * bodies_.walls.size(), 0.0);
}

template <int D>
void SdpdBackend::body_forces_at(const Y& y, Rates& out) const {
  const double h = kernel_.support();
  const SdpdMomentumTerm momentum{sdpd::viscosity_factor<D>() * model_.shear_viscosity};
  const double* x = y.x.data();
  out.body.assign(6 * bodies_.walls.size(), 0.0);
  for (std::size_t b = 0; b < bodies_.walls.size(); ++b) {
    std::array<double, 3> force{}, torque{};
    for (const std::uint32_t w : bodies_.walls[b]) {
      std::array<double, D> on_fluid{};  // sum over f of the pair force on f from w
      PairGeometry<D> g{};
      for (const std::uint32_t f : nlist_.of(w)) {
        if (wall_[f] || (open_.enabled() && open_.buffer(f))) continue;
        if (!pair_geometry<D>(x, f, w, g)) continue;  // x_fw = x_f - x_w
        std::array<double, D> v;
        for (int a = 0; a < D; ++a) v[a] = y.v[3 * f + a] - y.v[3 * w + a];
        fluid_pair_momentum<D>(y, f, w, g, v, momentum, h, on_fluid);  // as the gather
      }
      double r[3] = {x[3 * w] - bodies_.reference[b][0], x[3 * w + 1] - bodies_.reference[b][1],
                     x[3 * w + 2] - bodies_.reference[b][2]};
      pbox_.minimum_image(r);
      std::array<double, 3> fw{};
      for (int a = 0; a < D; ++a) fw[a] = -on_fluid[a];
      for (int a = D; a < 3; ++a) r[a] = 0.0;
      for (int a = 0; a < 3; ++a) force[a] += fw[a];
      torque[0] += r[1] * fw[2] - r[2] * fw[1];
      torque[1] += r[2] * fw[0] - r[0] * fw[2];
      torque[2] += r[0] * fw[1] - r[1] * fw[0];
    }
    for (int a = 0; a < 3; ++a) {
      out.body[6 * b + a] = force[a];
      out.body[6 * b + 3 + a] = torque[a];
    }
  }
}

void SdpdBackend::accumulate_body_forces(double dt) {
  for (std::size_t k = 0; k < bodies_.sum.size(); ++k) {
    bodies_.sum[k] += 0.5 * dt * (r0_.body[k] + r1_.body[k]);
  }
  bodies_.duration += dt;
}

std::vector<BodyForce> SdpdBackend::take_body_forces() {
  std::vector<BodyForce> out(bodies_.walls.size());
  const double inv_t = bodies_.duration > 0 ? 1.0 / bodies_.duration : 0.0;
  for (std::size_t b = 0; b < out.size(); ++b) {
    out[b].name = model_.body_forces[b].name;
    out[b].reference = bodies_.reference[b];
    for (int a = 0; a < 3; ++a) {
      out[b].force[a] = bodies_.sum[6 * b + a] * inv_t;
      out[b].torque[a] = bodies_.sum[6 * b + 3 + a] * inv_t;
    }
  }
  std::fill(bodies_.sum.begin(), bodies_.sum.end(), 0.0);
  bodies_.duration = 0;
  return out;
}

template void SdpdBackend::body_forces_at<1>(const Y&, Rates&) const;
template void SdpdBackend::body_forces_at<2>(const Y&, Rates&) const;
template void SdpdBackend::body_forces_at<3>(const Y&, Rates&) const;

}  // namespace sadr::fluid
