// SPDX-License-Identifier: MIT
/// \file sdpd_pair_physics.hpp
/// The SDPD pair physics, written once: each function is one equation of docs/method.md
/// section 2, on scalars, so that every path of the backend evaluates the same arithmetic in
/// the same order: the evaluators below (SdpdMomentumTerm, ContinuityTerm; the full-list
/// gather with walls and species, sdpd_gather.cpp), the SIMD block (sdpd_pair_block.cpp) and
/// the j side of the half path (sdpd_half_path.cpp). The files that vectorise them are compiled
/// without FMA contraction, so a pair gives the same bits in a SIMD lane and in a scalar loop.
///
/// Notation: x_ij = x_i - x_j, r = |x_ij|, v_ij = v_i - v_j, F_ij = -(1/r) dW/dr >= 0,
/// number density d_i = rho_i / m_i, P_i the pressure.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>

#include "sadr/fluid/pair_terms.hpp"

namespace sadr::fluid::sdpd {

/// Pressure factor of the momentum equation, (P_i/d_i^2 + P_j/d_j^2) F_ij.
inline double pressure_factor(double pd2_i, double pd2_j, double f) {
  return (pd2_i + pd2_j) * f;
}

/// Viscous factor of the momentum equation, c_D eta F_ij / (d_i d_j).
/// @param inv_didj 1/(d_i d_j), formed by the caller as (1/d_i)(1/d_j).
inline double viscous_factor(double friction, double f, double inv_didj) {
  return friction * f * inv_didj;
}

/// Component a of the pair force on i (Espanol & Revenga 2003, docs/method.md (16)):
/// \f$ f_p x_a - f_v [v_a + x_a (x\cdot v)/r^2] \f$ with c = (x.v)/r^2.
inline double force_component(double fp, double fv, double x, double v, double c) {
  return fp * x - fv * (v + x * c);
}

/// The pair's term of drho_i/dt: continuity and the Molteni & Colagrossi (2009) density
/// diffusion (drawert2019 eqs 15, 18):
/// \f$ -m_j F_{ij} (x_{ij}\cdot v_{ij}) + 2\delta h c_0 V_j (\rho_j - \rho_i) F_{ij}
///     \frac{r^2}{r^2 + \epsilon_h h^2} \f$ (eps_h = 0.01).
/// @param two_dhc0 2 delta h c0 [length^2/time], @param eps_h2 eps_h h^2 [length^2].
inline double density_rate(double m_j, double f, double xv, double two_dhc0, double vol_j,
                           double rho_i, double rho_j, double r2, double eps_h2) {
  return -m_j * f * xv + two_dhc0 * vol_j * (rho_j - rho_i) * f * r2 / (r2 + eps_h2);
}

/// Thermal-noise amplitude of the pair, sqrt(amp2/2) = sqrt(2 k_B T c_D eta) sqrt(F_ij)
/// sqrt(1/d_i) sqrt(1/d_j), the last product formed symmetrically so both sides of the pair
/// get the same value (PairNoise, pair_terms.hpp).
inline double noise_amplitude(double noise_amp, double sqrt_f, double sqrt_inv_nd_i,
                              double sqrt_inv_nd_j) {
  return (noise_amp * sqrt_f) * (sqrt_inv_nd_i * sqrt_inv_nd_j);
}

/// Transport velocity (Adami, Hu & Adams 2013): the pair's term of the force of the uniform
/// pressure p_b (the paper's background pressure; scene parameter shift_pressure) on i, p_b (V_i^2
/// + V_j^2) F_ij x_ij = -p_b (V_i^2 + V_j^2) grad_i W_ij, the same form as the pressure term with
/// P/d^2 = p_b V^2 on both sides (pressure_factor).
/// @param pb_vi2 p_b V_i^2, @param pb_vj2 p_b V_j^2.
inline double shift_factor(double pb_vi2, double pb_vj2, double f) {
  return pressure_factor(pb_vi2, pb_vj2, f);
}

/// Component a of the pair's term of the A tensor in the momentum equation (Adami et al. 2013,
/// momentum equation): (V_i^2 + V_j^2) 1/2 (A_i + A_j) . grad_i W_ij with A = rho v (v~ - v) (outer
/// product) and grad_i W_ij = -F_ij x_ij, i.e. \f$ -\tfrac12 (V_i^2 + V_j^2) F_{ij} [\rho_i v_{i,a}
/// (s_i\cdot x_{ij})
///      + \rho_j v_{j,a} (s_j\cdot x_{ij})] \f$, s = v~ - v.
/// @param half_vf (V_i^2 + V_j^2) F_ij / 2, @param rho_sx_i rho_i (s_i . x_ij),
/// @param rho_sx_j rho_j (s_j . x_ij).
inline double a_tensor_component(double half_vf, double vi, double rho_sx_i, double vj,
                                 double rho_sx_j) {
  return -half_vf * (vi * rho_sx_i + vj * rho_sx_j);
}

/// c_D of the viscous term, a = b = c_D eta: 2 (D + 2) / (D + 3), 5/3 in 3D (LAMMPS,
/// Espanol-Revenga with zeta = 0), 8/5 in 2D, 3/2 in 1D, so that the continuum limit has shear
/// viscosity eta in every dimension (docs/fluid-core.md).
template <int D>
constexpr double viscosity_factor() {
  return 2.0 * (D + 2) / (D + 3);
}

/// Adami, Hu & Adams (2012) generalized wall (sdpd_adami_walls.cpp): the pair's terms of the
/// sums of wall particle w over its fluid neighbours f, with W_wf the kernel weight and x_wf =
/// x_w - x_f: the weight W_wf, p_f W_wf, v_f W_wf and rho_f (b . x_wf) W_wf with b = g - a_w the
/// body acceleration relative to the wall's (a_w: 0 for walls at rest; sdpd_adami_walls.cpp folds a
/// moving body's into g).
inline double adami_hydrostatic_term(double rho_f, double bx, double w) {
  return rho_f * bx * w;
}

/// Adami et al. 2012 eq 27: the wall pressure p_w = (sum_f p_f W_wf + sum_f rho_f (b . x_wf)
/// W_wf) / sum_f W_wf.
inline double adami_wall_pressure(double sum_pw, double sum_hydro, double sum_w) {
  return (sum_pw + sum_hydro) / sum_w;
}

/// Adami et al. 2012 eqs 22-23: component a of the wall velocity in the viscous term (no-slip),
/// 2 v_wall - sum_f v_f W_wf / sum_f W_wf.
inline double adami_wall_velocity(double v_wall, double sum_vw, double sum_w) {
  return 2.0 * v_wall - sum_vw / sum_w;
}

/// Adami walls on a surface of the geometry (sdpd_adami_walls.cpp): the sums of a wall particle
/// over its fluid neighbours f at distances s_f from the surface, with weights W_wf, for the
/// least-squares fit u_a(s) = v_wall + alpha s + gamma s^2 of each velocity component.
template <int D>
struct SurfaceFit {
  /// The fit is used when det >= kConditioning S2 S4 (S_k = sum_f W s^k): the distances spread
  /// enough to tell the curvature from the slope; else the linear extrapolation through the mean
  /// distance, r = d / max(S1 / S0, kMinDistance h), at most kMaxRatio. Either result is clamped
  /// to |v_w - v_wall| <= kMaxRatio max_f |v_f - v_wall|.
  static constexpr double kConditioning = 0.1, kMinDistance = 1e-3, kMaxRatio = 3.0;
  double s1 = 0, s2 = 0, s3 = 0, s4 = 0;
  std::array<double, D> su1{}, su2{}, vmin{}, vmax{};
  bool any = false;

  void add(double s, double w, const double* v) {
    const double ws = w * s, ws2 = ws * s;
    s1 += ws;
    s2 += ws2;
    s3 += ws2 * s;
    s4 += ws2 * s * s;
    for (int a = 0; a < D; ++a) {
      su1[a] += ws * v[a];
      su2[a] += ws2 * v[a];
      vmin[a] = any ? std::min(vmin[a], v[a]) : v[a];
      vmax[a] = any ? std::max(vmax[a], v[a]) : v[a];
    }
    any = true;
  }
  /// Component a of the wall particle's velocity at `depth` behind the surface moving at v_wall,
  /// given v~ = sum_vw / sum_w and the kernel support h. The clamp keeps the thermal noise of a
  /// few neighbours from being amplified without bound; it does not bind on a smooth flow.
  [[nodiscard]] double wall_velocity(int a, double v_wall, double depth, double sum_vw,
                                     double sum_w, double h) const {
    const double det = s2 * s4 - s3 * s3;
    double dv = 0;  // v_w - v_wall
    if (det > 0 && det >= kConditioning * s2 * s4) {
      const double b1 = su1[a] - v_wall * s1, b2 = su2[a] - v_wall * s2;
      const double alpha = (b1 * s4 - b2 * s3) / det, gamma = (s2 * b2 - s3 * b1) / det;
      dv = -alpha * depth + gamma * depth * depth;
    } else {
      const double r = std::min(depth / std::max(s1 / sum_w, kMinDistance * h), kMaxRatio);
      dv = -r * (sum_vw / sum_w - v_wall);
    }
    const double bound =
        kMaxRatio * std::max(std::abs(vmax[a] - v_wall), std::abs(vmin[a] - v_wall));
    return v_wall + std::clamp(dv, -bound, bound);
  }
};

}  // namespace sadr::fluid::sdpd

namespace sadr::fluid {

/// The momentum equation as an evaluator over PairGeometry (the gather loop):
/// \f$ m_i \dot v_i = \sum_j (P_i/d_i^2 + P_j/d_j^2) F_{ij} x_{ij}
///      - \frac{5\eta}{3} \sum_j \frac{F_{ij}}{d_i d_j}\,[v_{ij} + e_{ij}(e_{ij}\cdot v_{ij})] \f$
/// in the LAMMPS `sdpd/taitwater/isothermal` form.
struct SdpdMomentumTerm {
  double friction;  ///< c_D eta: (5/3) eta in 3D (LAMMPS), 8/5 eta in 2D, 3/2 eta in 1D
                    ///< (SdpdBackend::make_pair_params)
  /// Adds the pair force on i [mass length/time^2] to `force`.
  /// @param pi_di2 P_i/d_i^2, @param pj_dj2 P_j/d_j^2, @param inv_didj 1/(d_i d_j), @param v v_ij.
  template <int D>
  void operator()(const PairGeometry<D>& g, double pi_di2, double pj_dj2, double inv_didj,
                  const std::type_identity_t<std::array<double, D>>& v,
                  std::type_identity_t<std::array<double, D>>& force) const {
    const double fp = sdpd::pressure_factor(pi_di2, pj_dj2, g.f);
    const double fv = sdpd::viscous_factor(friction, g.f, inv_didj);
    double xv = 0;
    for (int a = 0; a < D; ++a) xv += g.x[a] * v[a];
    const double c = xv * g.inv_r2;
    for (int a = 0; a < D; ++a) force[a] += sdpd::force_component(fp, fv, g.x[a], v[a], c);
  }
};

/// The continuity equation with density diffusion (sdpd::density_rate) over PairGeometry.
struct ContinuityTerm {
  double delta_h_c0;  ///< delta h c0 [length^2/time]
  double eps_h2;      ///< eps_h h^2 [length^2]
  /// The pair's term of drho_i/dt with V_j = m_j/rho_j precomputed.
  template <int D>
  [[nodiscard]] double with_volume(const PairGeometry<D>& g,
                                   const std::type_identity_t<std::array<double, D>>& v, double m_j,
                                   double volume_j, double rho_i, double rho_j) const {
    double xv = 0;
    for (int a = 0; a < D; ++a) xv += g.x[a] * v[a];
    return sdpd::density_rate(m_j, g.f, xv, 2.0 * delta_h_c0, volume_j, rho_i, rho_j, g.r2, eps_h2);
  }
};

}  // namespace sadr::fluid
