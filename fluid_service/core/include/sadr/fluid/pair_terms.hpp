// SPDX-License-Identifier: MIT
/// \file pair_terms.hpp
/// Pair terms every particle backend may use (one term, one struct), each with its equation:
/// the pair geometry, the species diffusion coefficient and the thermal pair noise. They are
/// evaluated from the side of particle i in a gather loop over a full neighbour list; every
/// term is exactly antisymmetric (forces) or symmetric (coefficients) under i <-> j, so
/// momentum and species mass are conserved to round-off. The SDPD momentum and continuity
/// terms are the sdpd backend's (backends/sdpd/sdpd_pair_physics.hpp).
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
