// SPDX-License-Identifier: MIT
/// \file sdpd_transport_velocity.cpp
/// The transport-velocity formulation (Adami, Hu & Adams 2013; docs/fluid-core.md): after the
/// rates of a state are evaluated and the sub-step dt is known, two passes over the full lists
/// (sdpd_pair_physics.hpp: shift_factor, a_tensor_component):
///  1. the shift s_i = v~_i - v_i = (dt/2) (p_b/m_i) sum_j (V_i^2 + V_j^2) F_ij x_ij, the
///     shift-pressure push of the paper's kick-drift-kick (its half kick) in the
///     trapezoidal scheme: positions move with v + s, which displaces a particle by
///     dt^2/2 p_b-acceleration per sub-step as the paper's scheme does;
///  2. the A-tensor term (1/m_i) sum_j (V_i^2 + V_j^2) 1/2 (A_i + A_j) . grad_i W_ij with
///     A = rho v s, added to the deterministic acceleration.
/// Wall particles get no shift and no A term (v = 0 there); as neighbours they push through
/// the shift pressure. Deterministic: the thermal noise stays on the momentum equation.
#include <cmath>

#include "sadr/fluid/parallel.hpp"
#include "sdpd_backend.hpp"

namespace sadr::fluid {

template <int D>
void SdpdBackend::transport_velocity_terms(const Y& y, double dt, Rates& out) {
  const std::size_t n = mass_.size();
  const auto ni = static_cast<std::int64_t>(n);
  const double* x = y.x.data();
  out.shift.assign(3 * n, 0.0);
  const double pb = tvf_shift_pressure_;
#pragma omp parallel for schedule(static) if (ni > kMinParallel)
  for (std::int64_t ii = 0; ii < ni; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    if (wall_[i]) continue;
    const double pb_vi2 = pb * vol_[i] * vol_[i];
    std::array<double, D> push{};
    PairGeometry<D> g{};
    for (const std::uint32_t j : nlist_.of(i)) {
      if (!pair_geometry<D>(x, i, j, g)) continue;
      const double fb = sdpd::shift_factor(pb_vi2, pb * vol_[j] * vol_[j], g.f);
      for (int a = 0; a < D; ++a) push[a] += fb * g.x[a];
    }
    const double scale = 0.5 * dt / mass_[i];
    for (int a = 0; a < D; ++a) out.shift[3 * i + a] = scale * push[a];
  }
#pragma omp parallel for schedule(static) if (ni > kMinParallel)
  for (std::int64_t ii = 0; ii < ni; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    if (wall_[i]) continue;
    const double vi2 = vol_[i] * vol_[i];
    const double* vi = &y.v[3 * i];
    const double* si = &out.shift[3 * i];
    std::array<double, D> force{};
    PairGeometry<D> g{};
    for (const std::uint32_t j : nlist_.of(i)) {
      if (!pair_geometry<D>(x, i, j, g)) continue;
      const double* vj = &y.v[3 * j];
      const double* sj = &out.shift[3 * j];
      double sx_i = 0, sx_j = 0;
      for (int a = 0; a < D; ++a) {
        sx_i += si[a] * g.x[a];
        sx_j += sj[a] * g.x[a];
      }
      const double half_vf = 0.5 * (vi2 + vol_[j] * vol_[j]) * g.f;
      const double rsi = y.rho[i] * sx_i, rsj = y.rho[j] * sx_j;
      for (int a = 0; a < D; ++a)
        force[a] += sdpd::a_tensor_component(half_vf, vi[a], rsi, vj[a], rsj);
    }
    const double inv_m = 1.0 / mass_[i];
    for (int a = 0; a < D; ++a) out.acc[3 * i + a] += force[a] * inv_m;
  }
}

void SdpdBackend::apply_transport_velocity(const Y& y, double dt, Rates& out) {
  switch (model_.box.dimension) {
    case 1:
      transport_velocity_terms<1>(y, dt, out);
      break;
    case 2:
      transport_velocity_terms<2>(y, dt, out);
      break;
    default:
      transport_velocity_terms<3>(y, dt, out);
      break;
  }
}

}  // namespace sadr::fluid
