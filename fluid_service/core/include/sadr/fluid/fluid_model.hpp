// SPDX-License-Identifier: MIT
/// \file fluid_model.hpp
/// Everything a fluid backend needs to know about a scene besides the particle arrays.
///
/// Units: one consistent system chosen by the scene (SI in the validation cases).
/// d is the box dimension; "mass density" is mass/length^d; concentrations are
/// amounts per unit volume [C] = amount/length^d.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sadr/common/particle_state.hpp"
#include "sadr/common/rate_law.hpp"
#include "sadr/common/rigid_motion.hpp"
#include "sadr/common/wall_surface.hpp"
#include "sadr/model/chemistry.hpp"

namespace sadr::fluid {

/// Boundary condition of one species on one group of wall particles.
struct WallCondition {
  enum class Type {
    kNoFlux,     ///< wall particles do not exchange the species (homogeneous Neumann)
    kDirichlet,  ///< wall particles hold `value` [C] at all times
    kNeumann,    ///< a flux `value` [C length/time] enters the fluid through the wall
    kFree,       ///< wall particles take part in the species' diffusion and reactions exactly
                 ///< like fluid particles (exchange with neighbours, integrated by eq 17,
                 ///< reactions whose `kinds` include kWall fire there); they never move
  };
  Type type = Type::kNoFlux;
  double value = 0.0;
};

/// A group of wall particles: the listed particle indices if `particles` is non-empty, else
/// every wall particle whose position lies in [lo, hi] (inclusive, active axes only).
/// A wall particle belongs to the first region that contains it.
struct WallRegion {
  std::string name;
  std::vector<std::uint32_t> particles;  ///< explicit membership (indices into the initial state)
  std::array<double, 3> lo{0, 0, 0};     ///< [length]
  std::array<double, 3> hi{0, 0, 0};     ///< [length]
  /// Unit normal pointing from the wall into the fluid (kNeumann walls, Morris walls).
  std::array<double, 3> inward_normal{1, 0, 0};
  /// A point on the wall surface (the centre if surface_radius > 0) [length]; used by
  /// WallModel::kMorrisExtrapolated.
  std::array<double, 3> surface_point{0, 0, 0};
  /// 0: the surface is the plane through surface_point normal to inward_normal; > 0: a circle
  /// (2D) / sphere (3D) of this radius around surface_point, the fluid outside [length].
  double surface_radius = 0.0;
  /// The surface as common/wall_surface.hpp has it (distances, Morris beta).
  [[nodiscard]] WallSurface surface() const {
    return {surface_point, inward_normal, surface_radius};
  }
};

/// Velocity boundary condition of the wall particles (no-slip in both cases).
enum class WallModel {
  kStationary,          ///< wall particles keep v = 0 (the default; docs/method.md section 2)
  kMorrisExtrapolated,  ///< Morris, Fox & Zhu 1997: in the viscous term of a fluid-wall pair the
                        ///< wall velocity is -(d_j/d_i) v_i, i.e. v_ij = beta v_i with
                        ///< beta = min(1.5, 1 + d_j/d_i), d = distance to the region's wall
                        ///< surface (plane, circle or sphere), or to the wall particle's own
                        ///< tangent plane (FluidModel::wall_tangents)
  kAdami,  ///< Adami, Hu & Adams 2012: each wall particle's pressure and velocity extrapolated
           ///< from its fluid neighbours (kernel-weighted, with the hydrostatic term of the
           ///< gravity); the pressure (and the density from it by the inverse Tait law) in the
           ///< pressure term and 2 v_wall - <v_f> in the viscous term of fluid-wall pairs
};

/// The scene's name of a wall model ("stationary", "morris", "adami"; the schema's names).
[[nodiscard]] inline const char* wall_model_name(WallModel m) {
  switch (m) {
    case WallModel::kMorrisExtrapolated:
      return "morris";
    case WallModel::kAdami:
      return "adami";
    default:
      return "stationary";
  }
}

/// One chemical species carried by the particles: the model's (sadr/model/chemistry.hpp),
/// indexed by its position in FluidModel::species, and its wall conditions by region index.
/// Read `def.name` and `def.diffusivity` (kappa [length^2/time], >= 0). `def.stochastic` false
/// (deterministic(), the default here): the fluid backend integrates it (eq (17) with reactions,
/// docs/method.md section 2); true: a stochastic species owned by the SSA, the backend only
/// stores the values set by set_concentrations() (used e.g. for a Boussinesq feedback).
/// `def.boundaries` (by region name) are not read: default_wall and wall_conditions are what
/// they compile to.
struct SpeciesSpec {
  model::Species def;
  /// Condition on wall particles outside every WallRegion.
  WallCondition default_wall{};
  /// One condition per FluidModel::wall_regions entry, or empty (default_wall everywhere).
  std::vector<WallCondition> wall_conditions;

  SpeciesSpec() { def.stochastic = false; }
  explicit SpeciesSpec(model::Species species) : def(std::move(species)) {}
  /// By name and numbers (a FluidModel built without the model layer: tests, benches).
  SpeciesSpec(std::string name, double diffusivity, bool deterministic = true,
              WallCondition default_wall = {}, std::vector<WallCondition> wall_conditions = {});
  [[nodiscard]] bool deterministic() const { return !def.stochastic; }
};

/// Reaction among deterministic species, in concentration units: the model's
/// (sadr/model/chemistry.hpp) with its species and regions as indices. Mass action
/// (`def.rate` [C^(1 - order) / time]) or another rate law (`def.law`, common/rate_law.hpp,
/// v = law(C), species by FluidModel::species names; `def.rate` is then unused).
/// Rate of reaction: v = rate * prod_s C_s^nu_s / nu_s!  (the 1/nu! matches the RDME
/// combinatorics, so A + A -> 0 with `rate` k gives dC_A/dt = -k C_A^2, docs/method.md section 4).
/// dC_s/dt += (products_s - reactants_s) * v. `def.kinds`: the kinds where it fires (empty =
/// fluid particles only). `def.boundary_areas`: non-empty for a boundary flux (scene
/// `boundary_fluxes`), parallel to `particles` (then required): A_i [length^(d-1)] > 0, particle
/// i's share of the boundary area; the law is a flux density j [C length/time] into the fluid
/// and dC_s/dt += delta_s j A_i / V_i with V_i = m_i / rho_i at initialize() (docs/method.md
/// 4d). `def.reactants`, `def.products` (by name) and `def.regions` are not read: the indices
/// below are what they compile to.
struct ReactionSpec {
  model::Reaction def;
  std::vector<std::pair<int, int>> reactants;  ///< (species index, stoichiometry >= 1)
  std::vector<std::pair<int, int>> products;   ///< (species index, stoichiometry >= 1)
  /// Optional restriction to these particle indices (into the initial state; def.regions'
  /// particles, sorted and unique, or def.boundary_particles for a boundary flux); empty = all.
  /// Checked against N at initialize().
  std::vector<std::uint32_t> particles;

  ReactionSpec() = default;
  /// A mass-action reaction by indices (a FluidModel built without the model layer: tests,
  /// benches).
  ReactionSpec(std::string name, std::vector<std::pair<int, int>> reactants,
               std::vector<std::pair<int, int>> products, double rate,
               std::vector<ParticleKind> kinds = {}, std::vector<std::uint32_t> particles = {});
};

/// Boussinesq body acceleration a = coefficient * (C_species - reference) * direction.
struct BoussinesqSpec {
  int species = -1;          ///< species index, -1 = off (any species, deterministic or not)
  double coefficient = 0.0;  ///< g * beta [length/time^2 / C]
  double reference = 0.0;    ///< C_ref [C]
  std::array<double, 3> direction{0, 1, 0};  ///< unit vector
};

enum class DensityMode {
  kContinuity,  ///< drho/dt from the continuity equation + Molteni-Colagrossi diffusion (default)
  kSummation,   ///< rho_i = sum_j m_j W_ij (eq (19), docs/method.md section 2)
};

enum class NoiseDistribution {
  kGaussian,  ///< Wiener increments (default)
  kUniform,   ///< zero-mean unit-variance uniform increments (same covariance; weak order 1)
};

/// Open (non-periodic) inflow/outflow along one axis (SDPD backend; docs/fluid-core.md 2).
/// Along `axis`: inlet buffer [inlet_lo, fluid_lo), fluid [fluid_lo, fluid_hi), outlet buffer
/// [fluid_hi, outlet_hi]. Non-wall particles change kind by position after every sub-step
/// (inlet -> fluid -> outlet -> recycled inlet, shifted by -(outlet_hi - inlet_lo)); N is fixed.
struct OpenBoundary {
  enum class Profile { kUniform, kParabolic };
  bool enabled = false;
  int axis = 0;  ///< flow axis (0, 1, 2), walled in the box
  double inlet_lo = 0, fluid_lo = 0, fluid_hi = 0, outlet_hi = 0;  ///< [length]
  Profile profile = Profile::kUniform;
  double mean_velocity = 0;  ///< mean inflow speed U along +axis [length/time]
  /// kParabolic: u(s) = 6 U (s - wall_lo)(wall_hi - s)/(wall_hi - wall_lo)^2 on the cross axis
  /// (zero at the no-slip planes wall_lo, wall_hi, 0 outside; maximum 1.5 U).
  int cross_axis = 1;
  double wall_lo = 0, wall_hi = 0;  ///< [length]
  /// Inflow velocity component along `axis` at a position [length/time].
  [[nodiscard]] double inflow_speed(const double* x) const {
    if (profile == Profile::kUniform) return mean_velocity;
    const double s = x[cross_axis], w = wall_hi - wall_lo;
    if (!(s > wall_lo && s < wall_hi)) return 0.0;
    return 6.0 * mean_velocity * (s - wall_lo) * (wall_hi - s) / (w * w);
  }
};

/// A body whose hydrodynamic force and torque the backend reports (fluid.body_forces): its wall
/// particles (indices into the initial state; non-wall members are ignored).
struct BodyForceGroup {
  std::string name;
  std::vector<std::uint32_t> particles;
};

/// A body whose wall particles follow a rigid motion (docs/fluid-core.md "Moving walls"): the
/// backend sets their positions and velocities from the time at every sub-step (sdpd only).
struct MovingBody {
  std::string name;
  std::vector<std::uint32_t> particles;  ///< its wall particles (indices into the initial state)
  RigidMotion motion;                    ///< from the particles' initial positions at t = 0
};

/// The scene. validate() reports every problem at once.
struct FluidModel {
  Box box{};
  double smoothing_length = 0.0;           ///< kernel SUPPORT radius h [length]
  std::string kernel = "lucy";             ///< "lucy" | "wendland_c2"
  double reference_density = 1.0;          ///< rho_0 [mass/length^d]
  double sound_speed = 1.0;                ///< c_0 [length/time]; >= 0, sdpd needs > 0
  double shear_viscosity = 0.0;            ///< eta [mass/(length^(d-2) time)]
  double temperature = 0.0;                ///< k_B T [energy]; 0 = deterministic SPH (no draws)
  std::array<double, 3> gravity{0, 0, 0};  ///< constant body acceleration [length/time^2]
  std::vector<SpeciesSpec> species;
  std::vector<ReactionSpec> reactions;
  std::uint64_t seed = 0;

  DensityMode density_mode = DensityMode::kContinuity;
  double density_diffusion = 0.1;  ///< Molteni-Colagrossi delta (dimensionless)
  /// eps_h in r^2/(r^2 + eps_h h^2) of the species Laplacian (same as the RDME graph,
  /// docs/method.md section 4; 0 gives the unbiased operator).
  double diffusion_eps = 0.01;
  BoussinesqSpec boussinesq{};
  NoiseDistribution noise = NoiseDistribution::kGaussian;
  WallModel wall_model = WallModel::kStationary;

  /// Upper bound on the sub-step [time]: sub-steps are <= min(binding stability limit,
  /// max_time_step); 0 = the stability limits only. With force_time_step the sub-step is
  /// max_time_step even where it breaks a limit (warned once per limit, warn_forced_substep).
  double max_time_step = 0.0;
  bool force_time_step = false;
  /// Blow-up band: |rho/rho_0 - 1| must stay below this (dimensionless).
  double density_band = 0.5;
  /// Verlet skin as a fraction of h.
  double neighbor_skin = 0.15;
  /// Backend-specific numbers by name (e.g. tdpd: a, gamma, s1, r_cc, lambda, skin). Each
  /// backend rejects keys it does not know, naming them (sdpd and static take none).
  std::map<std::string, double> backend_parameters;
  /// The backend's file parameters by name (absolute paths; the backend reads and checks them).
  std::map<std::string, std::string> backend_files;
  std::vector<WallRegion> wall_regions;
  /// kMorrisExtrapolated with walls made by a scene's geometry: the tangent plane of every wall
  /// particle (common/wall_surface.hpp); then the regions' surfaces are not used. Empty: none.
  WallTangents wall_tangents;
  OpenBoundary open_boundary{};
  /// Bodies whose force and torque every step reports (StepReport::body_forces); empty: none.
  std::vector<BodyForceGroup> body_forces;
  /// Bodies whose wall particles move rigidly (sdpd; other backends refuse them); empty: none.
  std::vector<MovingBody> moving_bodies;

  /// Throws InvalidArgument naming every offending field with value and allowed range.
  void validate() const;
  /// Region index of every particle (-1 for non-wall particles and walls in no region); the
  /// first listed region that contains a wall particle wins. Throws InvalidArgument for an
  /// explicit particle index out of range.
  [[nodiscard]] std::vector<std::int32_t> assign_wall_regions(const ParticleState& state) const;
  /// Index of the species called `name`, or -1.
  [[nodiscard]] int species_index(const std::string& name) const;
};

}  // namespace sadr::fluid
