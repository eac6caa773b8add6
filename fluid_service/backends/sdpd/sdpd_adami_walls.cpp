// SPDX-License-Identifier: MIT
/// \file sdpd_adami_walls.cpp
/// Adami, Hu & Adams (2012) generalized wall boundary condition (WallModel::kAdami,
/// docs/fluid-core.md): once per force evaluation, before the fluid forces, every wall particle w
/// takes from its fluid neighbours f (kernel weights W_wf, x_wf = x_w - x_f; pair terms in
/// sdpd_pair_physics.hpp)
///  - the pressure p_w = (sum_f p_f W_wf + (g - a_w) . sum_f rho_f x_wf W_wf) / sum_f W_wf, with g
///    the gravity and a_w = 0 (walls never move), and the density rho_w from p_w by the inverse
///    Tait law: P_w/d_w^2 in the pressure term of fluid-wall pairs;
///  - the velocity 2 v_wall - sum_f v_f W_wf / sum_f W_wf (v_wall = 0) in the viscous term.
/// A wall particle without a fluid neighbour keeps p = 0 at the reference density and v = 0. The
/// wall's continuity density, its noise factor and its species terms are those of stationary
/// walls.
#include <algorithm>
#include <array>

#include "sadr/fluid/parallel.hpp"
#include "sdpd_backend.hpp"

namespace sadr::fluid {

template <int D>
void SdpdBackend::adami_wall_values(const Y& y) {
  const std::size_t n = mass_.size();
  const auto ni = static_cast<std::int64_t>(n);
  const double* x = y.x.data();
  adami_p_.assign(n, 0.0);
  adami_v_.assign(3 * n, 0.0);
  const double* grav = model_.gravity.data();
  // the densities of the blow-up band bound the wall's: 1 + p/B >= (1 - band)^7
  const double lo = std::max(1.0 - model_.density_band, 1e-3);
  const double lo7 = lo * lo * lo * lo * lo * lo * lo;
#pragma omp parallel for schedule(static) if (ni > kMinParallel)
  for (std::int64_t ii = 0; ii < ni; ++ii) {
    const auto w = static_cast<std::size_t>(ii);
    if (!wall_[w]) continue;
    double sum_w = 0, sum_pw = 0, sum_hydro = 0;
    std::array<double, D> sum_vw{};
    PairGeometry<D> g{};
    for (const std::uint32_t f : nlist_.of(w)) {
      if (wall_[f] || !pair_geometry<D>(x, w, f, g)) continue;
      const double wf = kernel_.w(g.r);
      double bx = 0;
      for (int a = 0; a < D; ++a) bx += grav[a] * g.x[a];
      sum_w += wf;
      sum_pw += eos_.pressure(y.rho[f]) * wf;
      sum_hydro += sdpd::adami_hydrostatic_term(y.rho[f], bx, wf);
      for (int a = 0; a < D; ++a) sum_vw[a] += y.v[3 * f + a] * wf;
    }
    if (sum_w <= 0.0) {  // no fluid neighbour: p = 0 at the reference density, v = 0
      pd2_[w] = 0.0;
      continue;
    }
    const double p = sdpd::adami_wall_pressure(sum_pw, sum_hydro, sum_w);
    const double nd_inv = mass_[w] / eos_.density(p, lo7);  // 1/d_w at rho_w(p_w)
    adami_p_[w] = p;
    pd2_[w] = p * nd_inv * nd_inv;
    for (int a = 0; a < D; ++a)
      adami_v_[3 * w + a] = sdpd::adami_wall_velocity(y.v[3 * w + a], sum_vw[a], sum_w);
  }
}

template void SdpdBackend::adami_wall_values<1>(const Y&);
template void SdpdBackend::adami_wall_values<2>(const Y&);
template void SdpdBackend::adami_wall_values<3>(const Y&);

}  // namespace sadr::fluid
