// SPDX-License-Identifier: MIT
/// \file tdpd_walls.hpp
/// Planar walls without frozen particles (li2015 sec. II B): effective boundary forces
/// (conservative f_C, dissipative gamma_tau / gamma_n with the paper's caps, random parts by
/// fluctuation-dissipation), effective concentration fluxes (Dirichlet via phi(h), Neumann via
/// the normalised Phibar(h)) and bounce-back reflection of particles that cross a wall.
///
/// The walls are the two faces (box.lo[k], box.hi[k]) of every non-periodic active axis k; the
/// wall is at rest. Enabled by FluidModel::backend_parameters["effective_walls"] = 1.
/// The fits are the paper's (rho = 4, a = 18.75, gamma = 4.5, r_c = r_cc = 1.58); the
/// combining prefactors are derived (docs/tdpd.md, "Walls without frozen particles"):
///   F_i += f_C(h) e_n - gamma_n(h) v_n e_n - gamma_tau(h) v_tau     (e_n: inward normal)
///          + sqrt(2 k_B T gamma_n(h) / dt) xi_n e_n + sqrt(2 k_B T gamma_tau(h) / dt) xi_tau
///   Dirichlet: dC_i/dt += kappa 2 pi rho phi(h_i) (C_w - C_i)
///   Neumann:   dC_i/dt += q rho_N A Phibar(h_i) / sum_j Phibar(h_j)   (q = inward flux of C)
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "sadr/fluid/fluid_model.hpp"

namespace sadr::fluid::tdpd {

/// The paper's fits, in the paper's units (r_c = r_cc = 1.58), as functions of q = h / r_c or
/// h / r_cc in [0, 1); zero beyond 1. Caps are applied by the caller.
inline double poly7(const double (&p)[7], double q) {
  if (q >= 1.0) return 0.0;
  const double u = 1.0 - q;
  double s = 0.0;
  for (double pi : p) s = s * u + pi;  // sum_i p_i u^(6-i), times u below: u^(7-i)
  return s * u;
}
/// f_C(h) [force], li2015 sec. II B (already includes a rho and g(r)).
inline double fit_fc(double q) {
  static constexpr double p[7] = {525.6666, -1457.0412, 1485.7229, -927.0881,
                                  453.3782, -7.2616,    0.17758};
  return poly7(p, q);
}
/// Phibar(h) [1/length] for r_cc = 1.58 (normalised to 1 on [0, r_cc] up to 0.9%).
inline double fit_phibar(double q) {
  static constexpr double p[7] = {22.74545, -62.6256, 55.1365, -19.2584, 6.2662, -0.50242, 0.0101};
  return poly7(p, q);
}
/// c0 / h [1 + c1 q + c2 q^2] (1 - q)^e with h = q r (the form of phi, gamma_tau, gamma_n).
inline double fit_inv_h(double c0, double c1, double c2, double e, double q, double r) {
  if (q >= 1.0) return 0.0;
  return c0 / (q * r) * (1.0 + c1 * q + c2 * q * q) * std::pow(1.0 - q, e);
}

/// One wall plane and, per species, its concentration condition.
struct WallPlane {
  int axis = 0;
  double position = 0.0;  ///< coordinate of the plane [length]
  double sign = 1.0;      ///< +1: fluid at larger coordinate (lower wall), -1: upper wall
  double area = 1.0;      ///< area of the plane [length^2]
  std::vector<WallCondition> species;
};

class EffectiveWalls {
 public:
  /// Reads the planes from the box and the per-species conditions from the model: the first
  /// WallRegion whose inward_normal points along +-axis supplies wall_conditions[region], else
  /// SpeciesSpec::default_wall. kFree acts as no-flux (there are no wall particles).
  void setup(const FluidModel& model, double a, double gamma, double r_cc, double rho);
  [[nodiscard]] bool enabled() const { return !planes_.empty(); }
  [[nodiscard]] const std::vector<WallPlane>& planes() const { return planes_; }

  /// Adds the effective boundary forces on the non-frozen particles (frozen[i] == 0).
  void add_forces(const std::vector<double>& x, const std::vector<double>& v,
                  const std::vector<std::uint8_t>& frozen, std::uint64_t seed,
                  std::uint64_t noise_key, std::uint32_t sub, double dt,
                  std::vector<double>& force) const;
  /// Adds the effective boundary fluxes of the transported species: the Neumann source
  /// q rho_N A Phibar(h_i) / sum_j Phibar(h_j) and, only if with_dirichlet (the reported rates of
  /// TdpdBackend::evaluate_current()), the Dirichlet rate k (C_w - C_i), k = kappa 2 pi rho
  /// phi(h). The integrator does not take the Dirichlet term as a flux (it is stiff: k dt = 6.8
  /// at the phi cap for kappa = 8.7, dt = 0.01); it applies relax_dirichlet() instead.
  void add_fluxes(const std::vector<double>& x, const std::vector<std::uint8_t>& frozen,
                  const std::vector<int>& transported, const std::vector<double>& kappa,
                  const std::vector<std::vector<double>>& c, std::vector<std::vector<double>>& flux,
                  bool with_dirichlet) const;
  /// Integrates the Dirichlet wall term dC_i/dt = k(h_i) (C_w - C_i) exactly over tau at fixed
  /// positions: C_i <- C_w + (C_i - C_w) exp(-k(h_i) tau), plane after plane. Unconditionally
  /// stable and bounded (a convex combination of C_i and C_w; the maximum principle holds).
  void relax_dirichlet(const std::vector<double>& x, const std::vector<std::uint8_t>& frozen,
                       const std::vector<int>& transported, const std::vector<double>& kappa,
                       double tau, std::vector<std::vector<double>>& c) const;
  /// Bounce-back reflection (x -> 2 x_w - x, v -> -v, v_pred -> -v_pred) of particles that
  /// crossed a plane. Returns the number reflected.
  std::size_t reflect(std::vector<double>& x, std::vector<double>& v, std::vector<double>& v_pred,
                      const std::vector<std::uint8_t>& frozen) const;

  /// Scaled fits at distance h [length] (testing aid and documentation).
  [[nodiscard]] double f_c(double h) const;
  [[nodiscard]] double gamma_tau(double h) const;
  [[nodiscard]] double gamma_n(double h) const;
  [[nodiscard]] double phi(double h) const;
  [[nodiscard]] double phibar(double h) const;

 private:
  std::vector<WallPlane> planes_;
  int dim_ = 3;
  double rc_ = 1.58, rcc_ = 1.58, kbt_ = 0.0, rho_ = 4.0;
  double scale_fc_ = 1.0, scale_gamma_ = 1.0, scale_phi_ = 1.0;
  double volume_ = 1.0;  ///< box volume [length^3]
};

/// Inflow/outflow concentration buffers along a periodic axis (li2015 sec. III B after Lei et
/// al.): particles in [lo, lo + inflow_length) hold C = inflow_value for every transported
/// species (no flux), and Fickian pairs across the periodic seam of the axis are cut, so the
/// outlet at hi is a zero-gradient (no-flux) boundary and no concentration diffuses from the
/// outlet into the inlet. Keys buffer_axis (0-2; -1 = off), inflow_length, inflow_value.
struct ConcentrationBuffers {
  int axis = -1;
  double lo = 0.0, inflow_end = 0.0, half_length = 0.0, value = 0.0;
  [[nodiscard]] bool enabled() const { return axis >= 0; }
  [[nodiscard]] bool in_inflow(const double* xi) const {
    return xi[axis] >= lo && xi[axis] < inflow_end;
  }
  /// True if the pair (i, j) interacts only through the periodic image along the axis.
  [[nodiscard]] bool across_seam(const double* xi, const double* xj) const {
    return std::abs(xi[axis] - xj[axis]) > half_length;
  }
  /// Sets C = value in the inflow buffer.
  void apply(const std::vector<double>& x, const std::vector<int>& transported,
             std::vector<std::vector<double>>& c) const {
    for (std::size_t i = 0; i < x.size() / 3; ++i) {
      if (!in_inflow(&x[3 * i])) continue;
      for (const int s : transported) c[static_cast<std::size_t>(s)][i] = value;
    }
  }
  /// Zeroes the rates of the inflow-buffer particles.
  void zero_inflow_flux(const std::vector<double>& x, const std::vector<int>& transported,
                        std::vector<std::vector<double>>& q) const {
    for (std::size_t i = 0; i < x.size() / 3; ++i) {
      if (!in_inflow(&x[3 * i])) continue;
      for (const int s : transported) q[static_cast<std::size_t>(s)][i] = 0.0;
    }
  }
};

}  // namespace sadr::fluid::tdpd
