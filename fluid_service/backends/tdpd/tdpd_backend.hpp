// SPDX-License-Identifier: MIT
/// \file tdpd_backend.hpp
/// Transport dissipative particle dynamics (tDPD, Li et al. 2015, J Chem Phys 143, 014101;
/// docs/method.md section 3) behind the FluidBackend seam, registered under the name "tdpd".
///
/// Model (unit particle mass, DPD units):
///  - pair force F_ij = [a w_C - gamma w_D (e_ij . v_ij) + sigma w_R xi_ij / sqrt(dt)] e_ij,
///    w_C = 1 - r/r_c, w_D = w_R^2 = (1 - r/r_c)^s1, sigma^2 = 2 gamma k_B T (r < r_c);
///  - per species Fickian flux dC_i/dt = sum_j kappa (1 - r/r_cc)^2 (C_j - C_i) (r < r_cc),
///    no random flux (as the paper), plus the mass-action reactions of the model;
///  - modified velocity-Verlet of Groot & Warren 1997 with lambda (default 0.5, li2015 ref 5);
///    concentrations are advanced by half steps around the flux evaluation (LAMMPS mvv/tdpd).
/// Noise xi_ij is keyed (seed, step, min(i,j), max(i,j)) so F_ij = -F_ji bit-exactly and the
/// result does not depend on the thread count. k_B T = 0 draws no random numbers.
/// Wall particles (kind kWall) are frozen: v = 0, they exert pair forces on fluid particles
/// and, per species, hold a Dirichlet value (exchange flux) or are excluded (no-flux).
/// With backend_parameters["effective_walls"] = 1 the faces of every non-periodic axis are
/// walls without frozen particles: effective boundary forces and concentration fluxes of
/// li2015 sec. II B and bounce-back reflection (tdpd_walls.hpp, docs/tdpd.md).
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "sadr/fluid/backend_base.hpp"
#include "sadr/fluid/backend_registry.hpp"
#include "sadr/fluid/kernel.hpp"
#include "sadr/fluid/neighbor_list.hpp"
#include "sadr/fluid/periodic_box.hpp"
#include "sadr/fluid/slab_scheduler.hpp"
#include "sadr/fluid/species_transport.hpp"
#include "sadr/fluid/stability.hpp"
#include "tdpd_cells.hpp"
#include "tdpd_walls.hpp"

namespace sadr::fluid {

/// tDPD parameters that FluidModel has no field for. FluidModel supplies the rest:
/// temperature = k_B T [energy], smoothing_length = r_c [length], reference_density = number
/// density rho [1/length^d] (used only by the stability limits), SpeciesSpec::def.diffusivity =
/// Fickian friction coefficient kappa [1/time] (NOT the effective D; see kappa_for()).
struct TdpdParameters {
  double a = 18.75;     ///< conservative force amplitude a_ij [force]
  double gamma = 4.5;   ///< dissipative coefficient [mass/time]
  double s1 = 0.41;     ///< exponent of w_D (dimensionless)
  double r_cc = 0.0;    ///< flux cutoff [length]; 0 = r_c; must be <= r_c
  double lambda = 0.5;  ///< Groot-Warren velocity-prediction factor (dimensionless)
  /// Verlet skin as a fraction of r_c; 0 = FluidModel::neighbor_skin. DPD particles move
  /// ~0.02 r_c per step at k_B T = 1, dt = 0.01, so a wider skin than SDPD's pays off.
  /// Narrowed automatically where a periodic axis is shorter than 2 r_c (1 + skin).
  double skin = 0.3;
  /// 1: walls without frozen particles on the non-periodic faces (li2015 sec. II B).
  bool effective_walls = false;
  /// Concentration inflow/outflow buffers (tdpd::ConcentrationBuffers): periodic axis or -1,
  /// inflow buffer length [length] from box.lo, value held there [C].
  int buffer_axis = -1;
  double inflow_length = 0.0;
  double inflow_value = 0.0;
  /// Throws InvalidArgument naming the field, value and allowed range.
  void validate(double r_c) const;
  /// Sets the fields named by FluidModel::backend_parameters; throws InvalidArgument for an
  /// unknown key (tdpd_parameters.cpp).
  void apply(const std::map<std::string, double>& kv);
};

class TdpdBackend final : public BackendBase {
 public:
  [[nodiscard]] std::string_view name() const override { return "tdpd"; }
  /// Parameters used by the next initialize() (defaults: the li2015 calibration set).
  void set_parameters(const TdpdParameters& p) { params_ = p; }
  [[nodiscard]] const TdpdParameters& parameters() const { return params_; }
  [[nodiscard]] double time() const override { return time_; }

  /// Stability limits at the current state [time] (acoustic, viscous, body_force, diffusion).
  [[nodiscard]] StabilityLimits current_limits() const;
  /// current_limits() under max_time_step / force_time_step (uniform_substeps' rule; tDPD's
  /// limits have no reaction term).
  [[nodiscard]] SubstepBound current_substep_bound() override {
    return substep_bound(current_limits(), model_.max_time_step, model_.force_time_step);
  }
  /// Pair forces (3N, [force]) and fluxes ([species][N], [C/time]) at the current state with
  /// the noise of (noise_step, dt) (testing aid; velocities as stored). With effective walls
  /// the fluxes include the wall terms, the Dirichlet one as the instantaneous rate
  /// kappa 2 pi rho phi(h) (C_w - C) (advance() integrates that term exactly instead).
  void evaluate_current(std::uint64_t noise_step, double dt, std::vector<double>& force,
                        std::vector<std::vector<double>>& flux);

  /// li2015 eq 12 (ideal gas g = 1, 3D): D = D_xi + D_F [length^2/time]; D_F = 2 pi rho kappa
  /// r_cc^5 / 315 for s2 = 2. Returned: the Fickian slope dD/dkappa [length^2].
  [[nodiscard]] static double fickian_slope_ideal(double rho, double r_cc);
  /// The effective walls (empty unless effective_walls; testing aid).
  [[nodiscard]] const tdpd::EffectiveWalls& effective_walls() const { return walls_; }
  /// Neighbour-list builds since initialize() (benchmark / testing aid; not saved).
  [[nodiscard]] std::uint64_t list_builds() const { return list_builds_; }
  /// Particles reflected at the effective walls so far.
  [[nodiscard]] std::uint64_t wall_reflections() const { return reflections_; }

 protected:
  /// FluidModel::validate() on a copy with shear_viscosity > 0: in tDPD the viscosity is an
  /// output of (a, gamma, rho, k_B T) and the field is ignored.
  void check_model(const FluidModel& model) const override;
  void setup(const FluidModel& model, const ParticleState& initial,
             const std::vector<std::vector<double>>& concentrations) override;
  StepReport step(std::uint64_t step_index, double time_step) override;
  void write_state(ParticleState& out) const override;
  std::vector<std::vector<double>>& fields() override { return c_; }
  const std::vector<std::vector<double>>& fields() const override { return c_; }
  const SpeciesTransport& transport() const override { return species_; }
  /// The stored fluxes belong to the old concentrations (the forces do not).
  void concentrations_changed() override { flux_stale_ = true; }
  /// 2: + list reference positions; 3: the stored rates exclude the effective-wall Dirichlet term
  std::uint32_t state_version() const override { return 3; }
  void save_state(BlobWriter& w) const override;
  void restore_state(BlobReader& r, std::uint32_t version) override;

 private:
  void evaluate(const std::vector<double>& x, const std::vector<double>& v,
                const std::vector<std::vector<double>>& c, std::uint64_t noise_key, double dt,
                std::vector<double>& force, std::vector<std::vector<double>>& flux,
                bool flux_only = false, bool dirichlet_rate = false);
  template <int D>
  void evaluate_dim(const std::vector<double>& x, const std::vector<double>& v,
                    const std::vector<std::vector<double>>& c, std::uint64_t noise_key, double dt,
                    std::vector<double>& force, std::vector<std::vector<double>>& flux,
                    bool flux_only);
  void ensure_neighbors() const;
  /// Builds the half list and its slabs at positions `ref` (tdpd_cells.hpp).
  void rebuild_neighbors(const std::vector<double>& ref) const;
  /// Runs per_particle(i, PairBlock&) over all particles in the order of the slab scheduler.
  template <class PerParticle>
  void slab_phases(PerParticle&& per_particle) const;
  void check_health(std::uint64_t step_index, std::uint32_t substep) const;
  /// Kernel-summed number densities rho_i = sum_j W(r_ij) (masses 1) [1/length^d].
  [[nodiscard]] std::vector<double> densities() const;

  TdpdParameters params_{};
  FluidModel model_;
  PeriodicBox pbox_;
  Kernel kernel_;
  std::unique_ptr<CellListBuilder> builder_;  ///< checks the box against the list cutoff
  /// Forward half list and slabs (tdpd_cells.hpp), rebuilt when a particle moved > skin/2.
  mutable tdpd::HalfList half_;
  mutable SlabScheduler slabs_;             ///< the slabs of half_ (core slab_scheduler.hpp)
  mutable std::vector<double> list_ref_x_;  ///< positions at the last list build (saved)
  mutable std::uint64_t list_builds_ = 0;
  double skin_half2_ = 0;
  SpeciesTransport species_;
  std::vector<double> kappa_;  ///< per species [1/time]
  std::vector<std::uint8_t> wall_;
  std::vector<ParticleKind> kinds_;
  std::vector<std::uint64_t> ids_;
  std::size_t n_ = 0;
  double r_cc_ = 0;
  double sigma_ = 0;

  // Dynamic state (all of it is saved).
  double time_ = 0;
  std::vector<double> x_, v_, f_;
  std::vector<std::vector<double>> c_, q_;
  bool have_forces_ = false;  ///< f_, q_ hold the rates at the current state
  bool flux_stale_ = false;   ///< q_ predates a set_concentrations()
  // Scratch.
  std::vector<double> v_pred_, f_new_;
  std::vector<double> cp_, qp_, okp_;  ///< particle-major C, flux sums, role masks
  std::vector<double> fsum_;           ///< pair force sums
  std::vector<double> rho_;            ///< kernel-summed number density at the last evaluation
  bool rho_valid_ = false;
  bool any_wall_ = false;
  std::vector<std::vector<double>> q_new_;
  tdpd::EffectiveWalls walls_;
  tdpd::ConcentrationBuffers buffers_;
  std::uint64_t reflections_ = 0;
};

/// Registers "tdpd" (called by the generated register_builtin_backends(), backends.cmake).
void register_tdpd_backend(BackendRegistry& registry);

}  // namespace sadr::fluid
