// SPDX-License-Identifier: MIT
/// \file rate_conversion.hpp
/// THE one place where macroscopic mass-action rate constants (concentration
/// units) become per-voxel stochastic rate constants (SPEC section 4).
///
/// With V = V_i = m_i / rho_i [L^d] and concentration C = X / V:
///
/// | order | reaction      | given k in       | c = mass_action_constant | propensity a      |
/// |-------|---------------|------------------|--------------------------|-------------------|
/// | 0     | 0 -> ...      | conc / T         | k V                      | c                 |
/// | 1     | A -> ...      | 1 / T            | k                        | c X_A             |
/// | 2     | A + B -> ...  | 1 / (conc T)     | k / V                    | c X_A X_B         |
/// | 2     | A + A -> ...  | 1 / (conc T)     | k / V                    | c X_A (X_A - 1)/2 |
///
/// Convention for A + A: k is defined by dC_A/dt = -k C_A^2 in the rate
/// equation (i.e. k C_A^2 / 2 reaction events per unit volume and time, each
/// consuming two A). So a = (k/V) X(X-1)/2, whose large-X limit reproduces
/// exactly dC_A/dt = -k C_A^2. For A + B (A != B) the propensity is the full
/// (k/V) X_A X_B: the paper's code uses k/(2V) there, which halves the rate
/// (a bug we do not copy). In general a = c prod_s binom(X_s, nu_s).
#pragma once

#include <cstdint>

namespace sadr::ssa {

/// Per-voxel stochastic rate constant c of a mass-action reaction.
/// @param k      macroscopic rate constant (units by order, see the table above)
/// @param order  total reaction order 0, 1 or 2
/// @param volume voxel volume V_i [L^d], > 0
/// @return c [1/T]: the propensity is c times the combinatorial factor
///         prod_s binom(X_s, nu_s) (combinatorial_factor()).
double mass_action_constant(double k, int order, double volume);

/// binom(x, nu) for nu = 1 or 2 (0 if x < nu): the number of distinct
/// reactant combinations of one species with stoichiometry nu.
inline double combinatorial_factor(std::int64_t x, int nu) {
  if (nu == 1) return static_cast<double>(x);
  // nu == 2 (orders above 2 are rejected by Model::validate)
  return x < 2 ? 0.0 : 0.5 * static_cast<double>(x) * static_cast<double>(x - 1);
}

}  // namespace sadr::ssa
