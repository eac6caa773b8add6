// SPDX-License-Identifier: MIT
/// \file mass_action.hpp
/// THE mass-action law and the RDME volume scaling (docs/method.md section 4),
/// used by both numerical cores: the SSA's propensities (ssa_service
/// ReactionTable) and the deterministic reaction rates (fluid_service
/// SpeciesTransport), so that the two agree for large copy numbers.
///
/// A reaction with reactant stoichiometries nu_s, total order n = sum nu_s and
/// rate constant k in concentration units runs, per unit volume, at
///
///     v = k prod_s C_s^nu_s / nu_s!        (deterministic)
///
/// and in voxel i (volume V_i = m_i / rho_i) with propensity
///
///     a_i = c_i prod_s binom(X_is, nu_s),  c_i = k V_i^(1 - n):
///
/// | order | reaction      | k in                  | c_i      | propensity        |
/// |-------|---------------|-----------------------|----------|-------------------|
/// | 0     | 0 -> ...      | molecules / (L^d T)   | k V      | c                 |
/// | 1     | A -> ...      | 1 / T                 | k        | c X_A             |
/// | 2     | A + B -> ...  | L^d / (molecules T)   | k / V    | c X_A X_B         |
/// | 2     | A + A -> ...  | L^d / (molecules T)   | k / V    | c X_A (X_A - 1)/2 |
///
/// So A + A with rate k gives dC_A/dt = -k C_A^2, and a / V -> v as X = C V
/// grows. For A + B the full (k/V) X_A X_B is used (drawert2019's code uses
/// k/(2V), which halves the rate: a bug not copied).
#pragma once

#include <cstdint>
#include <string>

#include "sadr/common/status.hpp"

namespace sadr::mass_action {

/// Per-voxel stochastic rate constant c = k V^(1 - order) [1/T].
/// @param k      rate constant in concentration units (see the table)
/// @param order  total reaction order 0, 1 or 2
/// @param volume voxel volume V_i > 0 [L^d]
inline double voxel_constant(double k, int order, double volume) {
  switch (order) {
    case 0:
      return k * volume;
    case 1:
      return k;
    case 2:
      return k / volume;
    default:
      throw InvalidArgument("reaction order = " + std::to_string(order) + " (allowed: 0, 1, 2)");
  }
}

/// binom(x, nu) for nu = 1 or 2 (0 if x < nu): the distinct reactant
/// combinations of one species with stoichiometry nu (orders above 2 are
/// refused by the models).
inline double combinations(std::int64_t x, int nu) {
  if (nu == 1) return static_cast<double>(x);
  return x < 2 ? 0.0 : 0.5 * static_cast<double>(x) * static_cast<double>(x - 1);
}

/// 1 / nu!, the deterministic law's combinatorial factor.
inline double inverse_factorial(int nu) {
  double fact = 1;
  for (int k = 2; k <= nu; ++k) fact *= k;
  return 1.0 / fact;
}

/// C^nu / nu! with inv_factorial = inverse_factorial(nu): C multiplied nu
/// times, then scaled (this order of operations is part of the results).
inline double concentration_term(double c, int nu, double inv_factorial) {
  double p = c;
  for (int k = 1; k < nu; ++k) p *= c;
  return p * inv_factorial;
}

}  // namespace sadr::mass_action
