// SPDX-License-Identifier: MIT
/// \file sdpd_adami_walls.cpp
/// Adami, Hu & Adams (2012) generalized wall boundary condition (WallModel::kAdami,
/// docs/fluid-core.md): once per force evaluation, before the fluid forces, every wall particle w
/// takes from its fluid neighbours f (kernel weights W_wf, x_wf = x_w - x_f; pair terms in
/// sdpd_pair_physics.hpp)
///  - the pressure p_w = (sum_f p_f W_wf + (g - a_w) . sum_f rho_f x_wf W_wf) / sum_f W_wf, with g
///    the gravity and a_w = 0 (walls do not accelerate), and the density rho_w from p_w by the
///    inverse Tait law: P_w/d_w^2 in the pressure term of fluid-wall pairs;
///  - the velocity of the viscous term: 2 v_wall - sum_f v_f W_wf / sum_f W_wf (v_wall the wall
///    particle's prescribed velocity, docs/fluid-core.md "Moving walls"), which
///    puts the no-slip surface about halfway between the fluid and the wall particles.
/// Walls made by a scene's geometry know their surface (FluidModel::wall_tangents: depth d_w
/// behind the tangent plane at the closest surface point p_w, normal n_w, and here the mean
/// curvature kappa_w there, adami_surfaces()), and put the no-slip surface on it instead: with
/// s_f = n_w . (x_f - p_w) - kappa_w |e_t|^2 / 2 the distance of f from the surface (e_t the part
/// of x_f - p_w along the plane), the weighted least-squares fit u = v_wall + alpha s + gamma s^2
/// of the fluid neighbours' velocities is extended to the wall particle, v_w = v_wall - alpha d_w
/// + gamma d_w^2, exact for a profile quadratic in the distance (Poiseuille flow); where the
/// neighbours' distances do not spread enough for the curvature (the deeper layers), the linear
/// v_w = v_wall - r (v~ - v_wall), r = d_w / (sum_f W_wf s_f / sum_f W_wf), at most 3; either is
/// clamped to |v_w - v_wall| <= 3 max_f |v_f - v_wall| (sdpd::SurfaceFit).
/// A wall particle without a fluid neighbour keeps p = 0 at the reference density and v = 0. The
/// wall's continuity density, its noise factor and its species terms are those of stationary
/// walls.
#include <algorithm>
#include <array>
#include <cmath>

#include "sadr/fluid/parallel.hpp"
#include "sdpd_backend.hpp"

namespace sadr::fluid {

void SdpdBackend::adami_surfaces() {
  adami_tangent_.clear();
  adami_kappa_.clear();
  const WallTangents& t = model_.wall_tangents;
  if (!adami_ || t.empty()) return;
  const std::size_t n = wall_.size();
  adami_tangent_.assign(n, -1);
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (t.particles[k] < n && wall_[t.particles[k]]) {
      adami_tangent_[t.particles[k]] = static_cast<std::int32_t>(k);
    }
  }
  // Mean curvature at each entry's surface point p_j = x_j + d_j n_j from its neighbours' (the
  // shape operator maps a step along the surface to minus the change of the normal):
  // kappa_w = -sum_j W_wj (n_j - n_w) . t_wj / sum_j W_wj |t_wj|^2, t_wj = p_j - p_w in w's
  // tangent plane; positive where the surface curves toward the fluid (inside a pipe), and
  // bounded by 1/h (edges and corners).
  NeighborList list;
  builder_->build(y_.x, list);
  const int dim = model_.box.dimension;
  const double h = kernel_.support();
  adami_kappa_.assign(t.size(), 0.0);
  for (std::size_t w = 0; w < n; ++w) {
    const std::int32_t kw = adami_tangent_[w];
    if (kw < 0) continue;
    const auto kws = static_cast<std::size_t>(kw);
    const double* nw = &t.normals[3 * kws];
    double num = 0, den = 0;
    for (const std::uint32_t j : list.of(w)) {
      const std::int32_t kj = adami_tangent_[j];
      if (kj < 0) continue;
      const auto kjs = static_cast<std::size_t>(kj);
      double d[3] = {y_.x[3 * j] - y_.x[3 * w], y_.x[3 * j + 1] - y_.x[3 * w + 1],
                     y_.x[3 * j + 2] - y_.x[3 * w + 2]};
      pbox_.minimum_image(d);
      double r2 = 0;
      for (int a = 0; a < dim; ++a) r2 += d[a] * d[a];
      if (r2 >= h * h) continue;
      const double* nj = &t.normals[3 * kjs];
      double dp[3] = {0, 0, 0}, along = 0;
      for (int a = 0; a < dim; ++a) {
        dp[a] = d[a] + t.depths[kjs] * nj[a] - t.depths[kws] * nw[a];
        along += dp[a] * nw[a];
      }
      double dn_dp = 0, dp2 = 0;
      for (int a = 0; a < dim; ++a) {
        const double ta = dp[a] - along * nw[a];
        dn_dp += (nj[a] - nw[a]) * ta;
        dp2 += ta * ta;
      }
      const double wgt = kernel_.w(std::sqrt(r2));
      num -= wgt * dn_dp;
      den += wgt * dp2;
    }
    if (den > 0) adami_kappa_[kws] = std::clamp(num / den, -1.0 / h, 1.0 / h);
  }
}

template <int D>
void SdpdBackend::adami_wall_values(const Y& y) {
  const std::size_t n = mass_.size();
  const auto ni = static_cast<std::int64_t>(n);
  const double* x = y.x.data();
  adami_p_.assign(n, 0.0);
  adami_v_.assign(3 * n, 0.0);
  const double* grav = model_.gravity.data();
  const double h = kernel_.support();
  // the densities of the blow-up band bound the wall's: 1 + p/B >= (1 - band)^7
  const double lo = std::max(1.0 - model_.density_band, 1e-3);
  const double lo7 = lo * lo * lo * lo * lo * lo * lo;
#pragma omp parallel for schedule(static) if (ni > kMinParallel)
  for (std::int64_t ii = 0; ii < ni; ++ii) {
    const auto w = static_cast<std::size_t>(ii);
    if (!wall_[w]) continue;
    double sum_w = 0, sum_pw = 0, sum_hydro = 0;
    std::array<double, D> sum_vw{};
    const std::int32_t k = adami_tangent_.empty() ? -1 : adami_tangent_[w];
    const auto ks = static_cast<std::size_t>(std::max(k, 0));
    const double* nk = k >= 0 ? &model_.wall_tangents.normals[3 * ks] : nullptr;
    const double depth = k >= 0 ? model_.wall_tangents.depths[ks] : 0.0;
    const double kappa = k >= 0 ? adami_kappa_[ks] : 0.0;
    sdpd::SurfaceFit<D> fit;
    PairGeometry<D> g{};
    // g - a_w: a moving body's wall accelerates (centripetal, omega^2 r, when it turns)
    std::array<double, 3> acc{grav[0], grav[1], grav[2]};
    if (!moving_.of.empty() && moving_.of[w] >= 0) {
      const std::array<double, 3> aw = moving_acceleration(w);
      for (int a = 0; a < 3; ++a) acc[a] -= aw[a];
    }
    for (const std::uint32_t f : nlist_.of(w)) {
      if (wall_[f] || !pair_geometry<D>(x, w, f, g)) continue;
      const double wf = kernel_.w(g.r);
      double bx = 0;
      for (int a = 0; a < D; ++a) bx += acc[a] * g.x[a];
      sum_w += wf;
      sum_pw += eos_.pressure(y.rho[f]) * wf;
      sum_hydro += sdpd::adami_hydrostatic_term(y.rho[f], bx, wf);
      for (int a = 0; a < D; ++a) sum_vw[a] += y.v[3 * f + a] * wf;
      if (nk) {  // e = x_f - p_w: n . e in front of the plane, less kappa |e_t|^2 / 2
        double s = 0, e2 = 0;
        for (int a = 0; a < D; ++a) {
          const double e = -g.x[a] - depth * nk[a];
          s += nk[a] * e;
          e2 += e * e;
        }
        fit.add(s - 0.5 * kappa * (e2 - s * s), wf, &y.v[3 * f]);
      }
    }
    if (sum_w <= 0.0) {  // no fluid neighbour: p = 0 at the reference density, v = 0
      pd2_[w] = 0.0;
      continue;
    }
    const double p = sdpd::adami_wall_pressure(sum_pw, sum_hydro, sum_w);
    const double nd_inv = mass_[w] / eos_.density(p, lo7);  // 1/d_w at rho_w(p_w)
    adami_p_[w] = p;
    pd2_[w] = p * nd_inv * nd_inv;
    for (int a = 0; a < D; ++a) {
      adami_v_[3 * w + a] = nk ? fit.wall_velocity(a, y.v[3 * w + a], depth, sum_vw[a], sum_w, h)
                               : sdpd::adami_wall_velocity(y.v[3 * w + a], sum_vw[a], sum_w);
    }
  }
}

template void SdpdBackend::adami_wall_values<1>(const Y&);
template void SdpdBackend::adami_wall_values<2>(const Y&);
template void SdpdBackend::adami_wall_values<3>(const Y&);

}  // namespace sadr::fluid
