// SPDX-License-Identifier: MIT
/// \file pair_terms.hpp
/// SDPD pair physics as small evaluators (one term, one struct), each with its equation.
/// All are evaluated from the side of particle i in a gather loop over a full
/// neighbour list; every term is exactly antisymmetric (forces) or symmetric
/// (coefficients) under i <-> j, so momentum and species mass are conserved to round-off.
///
/// Notation (docs/method.md section 2): x_ij = x_i - x_j, r = |x_ij|, e_ij = x_ij / r,
/// v_ij = v_i - v_j, F_ij = -(1/r) dW/dr >= 0, number density d_i = rho_i / m_i.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <type_traits>

#include "sadr/common/rng.hpp"
#include "sadr/fluid/fluid_model.hpp"
#include "sadr/fluid/pair_noise_batch.hpp"

namespace sadr::fluid {

/// Geometry of one pair seen from i.
template <int D>
struct PairGeometry {
  std::array<double, D> x;  ///< x_ij [length]
  double r2;                ///< |x_ij|^2
  double r;                 ///< |x_ij|
  double f;                 ///< F_ij [1/length^(d+2)]
  double inv_r2;            ///< 1/|x_ij|^2
};

/// Espanol & Revenga (2003) isothermal SDPD momentum, in the LAMMPS
/// `sdpd/taitwater/isothermal` form (docs/method.md (16)):
/// \f$ m_i \dot v_i = \sum_j (P_i/d_i^2 + P_j/d_j^2) F_{ij} x_{ij}
///      - \frac{5\eta}{3} \sum_j \frac{F_{ij}}{d_i d_j}\,[v_{ij} + e_{ij}(e_{ij}\cdot v_{ij})] \f$.
struct SdpdMomentumTerm {
  double friction;  ///< c_D eta: (5/3) eta in 3D (LAMMPS), 8/5 eta in 2D, 3/2 eta in 1D
                    ///< (SdpdBackend::make_pair_params)
  /// Adds the pair force on i [mass length/time^2] to `force`.
  /// @param pi_di2 P_i/d_i^2, @param pj_dj2 P_j/d_j^2, @param inv_didj 1/(d_i d_j), @param v v_ij.
  template <int D>
  void operator()(const PairGeometry<D>& g, double pi_di2, double pj_dj2, double inv_didj,
                  const std::type_identity_t<std::array<double, D>>& v,
                  std::type_identity_t<std::array<double, D>>& force) const {
    const double fp = (pi_di2 + pj_dj2) * g.f;
    const double fv = friction * g.f * inv_didj;
    double xv = 0;
    for (int a = 0; a < D; ++a) xv += g.x[a] * v[a];
    const double c = xv * g.inv_r2;
    for (int a = 0; a < D; ++a) force[a] += fp * g.x[a] - fv * (v[a] + g.x[a] * c);
  }
};

/// Continuity with Molteni & Colagrossi (2009) density diffusion (drawert2019 eqs 15, 18):
/// \f$ \dot\rho_i = \sum_j m_j F_{ij} (v_{ij}\cdot x_{ij})\cdot(-1)
///     + 2\delta h c_0 \sum_j V_j (\rho_j - \rho_i) F_{ij} \frac{r^2}{r^2 + \epsilon_h h^2} \f$
/// (the second sum is the Brookshaw Laplacian of rho with diffusivity delta h c0;
/// eps_h = 0.01 as in the paper).
struct ContinuityTerm {
  double delta_h_c0;  ///< delta h c0 [length^2/time]
  double eps_h2;      ///< eps_h h^2 [length^2]
  template <int D>
  [[nodiscard]] double operator()(const PairGeometry<D>& g,
                                  const std::type_identity_t<std::array<double, D>>& v, double m_j,
                                  double rho_i, double rho_j) const {
    double xv = 0;
    for (int a = 0; a < D; ++a) xv += g.x[a] * v[a];
    return with_volume(g, v, m_j, m_j / rho_j, rho_i, rho_j);
  }
  /// The same with V_j = m_j/rho_j precomputed.
  template <int D>
  [[nodiscard]] double with_volume(const PairGeometry<D>& g,
                                   const std::type_identity_t<std::array<double, D>>& v, double m_j,
                                   double volume_j, double rho_i, double rho_j) const {
    double xv = 0;
    for (int a = 0; a < D; ++a) xv += g.x[a] * v[a];
    return -m_j * g.f * xv +
           2.0 * delta_h_c0 * volume_j * (rho_j - rho_i) * g.f * g.r2 / (g.r2 + eps_h2);
  }
};

/// Brookshaw / Cleary-Monaghan Laplacian coefficient of docs/method.md (17):
/// \f$ \dot C_i = \sum_j K_{ij} (\kappa_i + \kappa_j)(C_j - C_i),\;
///     K_{ij} = \frac{m_j}{\rho_j} F_{ij} \frac{r^2}{r^2 + \epsilon h^2} \f$  [1/length^2].
struct DiffusionTerm {
  double eps_h2;  ///< eps h^2 [length^2] (FluidModel::diffusion_eps h^2)
  template <int D>
  [[nodiscard]] double coefficient(const PairGeometry<D>& g, double volume_j) const {
    return volume_j * g.f * g.r2 / (g.r2 + eps_h2);
  }
};

/// Thermal pair noise with the fluctuation-dissipation amplitude of the viscous term
/// above (Espanol & Revenga 2003; LAMMPS sdpd/taitwater/isothermal):
/// impulse on i over dt = sqrt(4 k_B T (5/3) eta F_ij/(d_i d_j) dt) * W_ij e_ij with W_ij a
/// symmetric matrix of Wiener increments (diagonal variance 1, off-diagonal 1/2).
/// W e has covariance (I + e e^T)/2, which we draw as (g + e g0)/sqrt(2) with d + 1
/// independent standard normals (g, g0): same law, fewer numbers. The numbers are
/// Philox4x32-10 of the key (seed, purpose, step, min(i,j), max(i,j)) (pair_noise_batch.hpp) and e
/// is oriented from min(i,j) to max(i,j), so the force on j is exactly minus the force on i. The
/// SDPD backend evaluates this term once per sub-step at the start-of-step state Y^n and uses the
/// same random force in predictor and corrector (Ito interpretation, as the Verlet scheme of
/// LAMMPS; evaluating the multiplicative amplitude at the predicted state would turn the
/// trapezoidal scheme into a Stratonovich one).
struct PairNoise {
  std::uint64_t seed = 0;
  NoiseDistribution distribution = NoiseDistribution::kGaussian;

  /// Four independent unit-variance, zero-mean numbers for the pair (lo, hi) at `step`
  /// (pair_noise_batch.hpp; the SDPD pair loop draws a whole neighbour list at once).
  [[nodiscard]] std::array<double, 4> draw(std::uint64_t step, std::uint32_t lo,
                                           std::uint32_t hi) const {
    float z[4];
    pair_noise_numbers(seed, step, lo, &hi, 1, distribution, &z[0], &z[1], &z[2], &z[3]);
    return {z[0], z[1], z[2], z[3]};
  }

  /// Adds the random force on i [mass length/time^2] for pair (i, j).
  /// @param amp2 4 k_B T (5/3) eta F_ij / (d_i d_j dt)  (variance scale of the force).
  template <int D>
  void add(const PairGeometry<D>& g, std::uint64_t step, std::uint32_t i, std::uint32_t j,
           double amp2, std::type_identity_t<std::array<double, D>>& force) const {
    const bool i_lo = i < j;
    const auto z = i_lo ? draw(step, i, j) : draw(step, j, i);
    const double sign = i_lo ? 1.0 : -1.0;
    const double scale = std::sqrt(0.5 * amp2) / g.r;  // e = x / r
    // force_i = sign * sqrt(amp2/2) * (g + e_lohi g0), with e_lohi = sign * e_ij.
    for (int a = 0; a < D; ++a)
      force[a] += sign * std::sqrt(0.5 * amp2) * z[a] + scale * g.x[a] * z[3];
  }
};

}  // namespace sadr::fluid
