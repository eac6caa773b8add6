// SPDX-License-Identifier: MIT
/// \file model.hpp
/// The reaction-diffusion model of ssa_service: species, mass-action reactions,
/// boundary conditions and the diffusion-graph parameters (docs/method.md section 4).
///
/// Units: one consistent system chosen by the scene. Lengths [L], time [T],
/// copy numbers are dimensionless; a voxel volume V_i = m_i / rho_i has units
/// [L^d] in d dimensions. Rate constants are given in concentration units and
/// converted per voxel by sadr::mass_action::voxel_constant() (common/mass_action.hpp),
/// the one place where that scaling lives.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "sadr/common/particle_state.hpp"
#include "sadr/common/rate_law.hpp"
#include "sadr/common/wall_surface.hpp"
#include "sadr/model/chemistry.hpp"

namespace sadr::ssa {

/// How the per-edge weight D_ij of the particle graph is formed (docs/method.md section 4):
/// kSymmetric d_ij = kappa D_ij, D_ij = 2 m_i m_j/(m_i+m_j) (rho_i+rho_j)/(rho_i rho_j) reg F_ij
/// (drawert2019 eq 28); kVolume d_ij = 2 kappa V_j F_ij reg (the default; its pure-diffusion
/// equilibrium is a uniform concentration, what the fluid's SPH concentration equation relaxes
/// to on non-uniform particles). One type with the scene's (sadr/model/chemistry.hpp).
using model::JumpConvention;
using model::SsaMethod;
using model::to_string;

/// One chemical species: the model's (sadr/model/chemistry.hpp), indexed by its position in
/// Model::species. Read `def.name`, `def.diffusivity` (kappa [L^2/T]; 0 = immobile, no
/// diffusion bookkeeping); its `def.boundaries` are compiled into Model::reservoirs, ::neumann
/// and ::free_walls.
struct Species {
  model::Species def;

  Species() = default;
  explicit Species(model::Species species) : def(std::move(species)) {}
  /// By name and diffusivity (a Model built without the model layer: tests, benches).
  Species(std::string name, double diffusivity);
};

/// A reaction: the model's (sadr/model/chemistry.hpp) and what the SSA derives from it, its
/// species and regions as indices. Mass action of total order 0, 1 or 2 (`def.rate`), or any
/// other rate law (`def.law`, common/rate_law.hpp; then any stoichiometry).
///
/// From `def` the core reads: `name`; `rate`, the rate constant in concentration units:
/// order 0 [conc/T], order 1 [1/T], order 2 [1/(conc T)], conc = molecules/L^d (for A + A the
/// convention is dC_A/dt = -k C_A^2, common/mass_action.hpp); `kinds`, the particle kinds where
/// it may fire (empty = fluid only); `law`, a law other than mass action (species by the names
/// of Model::law_names(); `rate` is then unused; propensity a_i = V_i v(X_i / V_i));
/// `boundary_areas`: non-empty for a boundary flux (scene `boundary_fluxes`), parallel to
/// `voxels` (then required): A_i [L^(d-1)] > 0, voxel i's share of the boundary area; the law
/// (required) is then a flux density j [molecules/(L^(d-1) T)] and a_i = A_i j(X_i / V_i).
/// `def.reactants`, `def.products` (by name) and `def.regions` are not read: the indices below
/// are what they compile to.
struct Reaction {
  model::Reaction def;
  std::vector<std::pair<int, int>> reactants;  ///< (species index, stoichiometry >= 1)
  std::vector<std::pair<int, int>> products;   ///< (species index, stoichiometry >= 1)
  /// Optional restriction to particle indices (def.regions' particles, sorted and unique, or
  /// def.boundary_particles for a boundary flux); empty = all.
  std::vector<std::uint32_t> voxels;

  Reaction() = default;
  /// A mass-action reaction by indices (a Model built without the model layer: tests, benches).
  Reaction(std::string name, std::vector<std::pair<int, int>> reactants,
           std::vector<std::pair<int, int>> products, double rate,
           std::vector<ParticleKind> kinds = {}, std::vector<std::uint32_t> voxels = {});
};

/// Dirichlet reservoir: wall particles hold round(C V_i) molecules of
/// `species`; jumps into them are absorbed, jumps out leave the count unchanged.
/// A species with at least one reservoir treats EVERY wall particle as a
/// reservoir: the one whose `voxels` lists it, else the one with empty `voxels`
/// (all walls), else C = 0 (absorbing). Species without a reservoir see the
/// walls as no-flux.
struct WallReservoir {
  int species = 0;
  double concentration = 0;           ///< C [molecules/L^d]
  std::vector<std::uint32_t> voxels;  ///< optional: only these wall particles; empty = all walls
};

/// Wall particles that take part in species `species` like fluid voxels (cell membranes):
/// molecules jump in and out of them with the ordinary graph rates, and reactions whose
/// `kinds` include kWall fire there. They never move (the fluid keeps them fixed).
///
/// For species s, a wall particle listed in a FreeWall of s (or every wall particle if that
/// FreeWall's `voxels` is empty) is an ordinary voxel for s: no reservoir, edges to all
/// neighbours that are ordinary for s (fluid or free) or reservoirs of s (absorbed there).
/// Explicit lists take precedence over "all walls": a wall listed by a WallReservoir of s is a
/// reservoir even if a FreeWall of s has empty `voxels`, and vice versa. A wall listed
/// explicitly by both, or an all-walls FreeWall together with an all-walls WallReservoir of
/// the same species, is an error. Listed indices must be wall particles (< N).
struct FreeWall {
  int species = 0;
  std::vector<std::uint32_t> voxels;  ///< wall particles; empty = every wall particle
};

/// Morris, Fox & Zhu (1997) extrapolated Dirichlet walls (docs/method.md section 4): the wall
/// particles `voxels` lie behind `surface`, and the reservoirs' held concentration sits on that
/// surface rather than on the particles. At every graph build the edges between a non-wall voxel
/// i and such a wall voxel j are scaled, in both directions, by beta_ij = morris_beta(d_j, d_i, h)
/// (common/wall_surface.hpp; d_j the depth of j behind the surface, d_i the distance of i in
/// front of it), so the mean flux between them is beta_ij (k_ji X_j - k_ij X_i), the SDPD Morris
/// term in expectation. Only reservoir species use those edges (no-flux species do not see the
/// walls); not together with free_walls (validate() refuses it). A wall voxel belongs to
/// the first listed MorrisWall that lists it; listed voxels that are not walls are ignored.
struct MorrisWall {
  std::vector<std::uint32_t> voxels;  ///< wall particles (non-empty)
  WallSurface surface;
};

/// Neumann source: a constant inward flux through the walls, realised as a
/// zeroth-order source in the first layer of fluid particles next to a wall.
struct NeumannSource {
  int species = 0;
  double flux = 0;  ///< molecules / (L^(d-1) T), >= 0
};

/// The complete RDME model.
struct Model {
  std::vector<Species> species;
  std::vector<Reaction> reactions;
  Box box;                       ///< domain; its dimension must match the particles
  double smoothing_length = 0;   ///< Lucy kernel support radius h [L]; edges join r < h
  double regularization = 0.01;  ///< eps in r^2 / (r^2 + eps h^2), >= 0
  JumpConvention convention = JumpConvention::kVolume;
  std::vector<WallReservoir> reservoirs;
  std::vector<NeumannSource> neumann;
  std::vector<FreeWall> free_walls;      ///< walls that are ordinary voxels for a species
  std::vector<MorrisWall> morris_walls;  ///< extrapolated Dirichlet walls (empty: off)
  /// The same with walls made by a scene's geometry: every listed wall voxel lies behind its own
  /// tangent plane (common/wall_surface.hpp WallTangents; d_i from the minimum-image
  /// displacement of i from the wall voxel). Not together with morris_walls. Empty: off.
  WallTangents morris_tangents;
  /// Hybrid reactions (docs/method.md section 4c): deterministic species the rate
  /// laws read, not simulated; their concentrations are inputs held constant over
  /// each advance (NsmSolver::set_inputs). Law species index ns + k is frozen_species[k].
  std::vector<std::string> frozen_species;
  /// kExact: the NSM; kAdaptive: diffusion of abundant (voxel, species) pairs leaped within
  /// `tolerance` (adaptive_leap.hpp, docs/method.md "Adaptive SSA"), the rest exact NSM.
  SsaMethod method = SsaMethod::kExact;
  double tolerance = 0.01;  ///< kAdaptive only: 0 < tolerance < 1

  /// Checks every field; throws InvalidArgument listing all problems, each with
  /// the field, the value and the allowed range.
  void validate() const;
  /// Index of the species called `name`; throws InvalidArgument listing the known names.
  [[nodiscard]] int species_index(std::string_view name) const;
  /// The species names, in index order (what rate laws are compiled against).
  [[nodiscard]] std::vector<std::string> species_names() const;
  /// species_names() then frozen_species: what rate laws are compiled against.
  [[nodiscard]] std::vector<std::string> law_names() const;
  /// 64-bit fingerprint of every field (used to refuse restoring a snapshot
  /// into a solver built with another model).
  [[nodiscard]] std::uint64_t fingerprint() const;
};

}  // namespace sadr::ssa
