// SPDX-License-Identifier: MIT
/// \file chemistry.hpp
/// The chemistry of a model, by name: species with their boundary conditions, reactions with
/// their rate laws, and the SSA's graph settings. The scene loader produces these, the wire
/// layer carries them (wire/model_proto.hpp) and each service compiles them to its own indexed
/// form; check() is the one set of range checks all three run.
///
/// Units: one consistent system chosen by the scene author; "d" is the dimension.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sadr/common/particle_state.hpp"
#include "sadr/common/rate_law.hpp"
#include "sadr/model/problems.hpp"

namespace sadr::model {

/// Per-species condition on the non-fluid particles of one region. The first four travel as
/// sadr.common.v1.WallCondition.
enum class BoundaryCondition {
  kNone,       ///< no-flux: the wall particles take no part for this species
  kDirichlet,  ///< the particles are reservoirs held at `value` [molecules/length^d]
  kNeumann,    ///< inward flux density `value` [molecules/(length^(d-1) time)]
  kFree,       ///< the particles exchange molecules like fluid particles but do not move
  kInflow,     ///< the particles inside the region's box or channel (any kind, re-evaluated
               ///< as they move) are reset to `value`: an inlet buffer
};
std::string_view to_string(BoundaryCondition condition);

struct SpeciesBoundary {
  std::string region;  ///< region name ("" = every wall particle)
  BoundaryCondition condition = BoundaryCondition::kNone;
  double value = 0.0;  ///< see BoundaryCondition
};

struct Species {
  std::string name;          ///< [A-Za-z_][A-Za-z0-9_]*, unique
  bool stochastic = true;    ///< integer copy numbers (ssa_service) or concentrations (fluid)
  double diffusivity = 0.0;  ///< kappa >= 0 [length^2/time]
  std::vector<SpeciesBoundary> boundaries;
};

struct StoichiometryEntry {
  std::string species;
  std::uint32_t count = 1;  ///< >= 1
  bool operator==(const StoichiometryEntry&) const = default;
};

/// One irreversible reaction ("A + B -> C"). Mass action (`rate`) or another rate law (`law`).
struct Reaction {
  std::string name;
  std::vector<StoichiometryEntry> reactants;  ///< total order <= 2 for mass action
  std::vector<StoichiometryEntry> products;
  /// Rate constant in concentration units: order 0 [molecules/(length^d time)],
  /// order 1 [1/time], order 2 [length^d/(molecules time)], A + A defined by
  /// dC/dt = -k C^2 (common/mass_action.hpp).
  double rate = 0.0;
  std::vector<ParticleKind> kinds;   ///< where it may fire; empty = fluid only
  std::vector<std::string> regions;  ///< empty = everywhere
  bool stochastic = true;            ///< among stochastic species (SSA) or deterministic (fluid)
  /// A law other than mass action; `rate` is then unused.
  std::optional<rate_law::Definition> law{};
  /// Hybrid reaction: the species of the other path its law reads (a stochastic reaction:
  /// deterministic species, frozen over each SSA stage; a deterministic one: stochastic
  /// species, as X / V from the back-transfer). Not on the wire: the services know their own.
  std::vector<std::string> reads_other{};
  bool uses_time = false;  ///< the law reads the time t
  /// Non-empty: a boundary flux: the law is a flux density j [molecules/(length^(d-1) time)]
  /// into the fluid, fired only in these particles, each with its share of the boundary's
  /// area [length^(d-1)] (boundary_areas, parallel); `regions` is then empty.
  std::vector<std::uint32_t> boundary_particles{};
  std::vector<double> boundary_areas{};
  [[nodiscard]] unsigned order() const;
};

/// How the per-edge weight of the particle graph is formed (docs/method.md section 4).
/// kVolume (the default) relaxes pure diffusion to a uniform concentration; kSymmetric
/// (drawert2019 eq 28) to equal counts per voxel; both coincide on uniform particles.
enum class JumpConvention { kSymmetric, kVolume };
std::string_view to_string(JumpConvention convention);

/// How ssa_service samples the RDME (docs/method.md "Adaptive SSA"): kExact, the exact Next
/// Subvolume Method (the default); kAdaptive, binomial leaps of the diffusion of abundant
/// (voxel, species) pairs within a tolerance, exact NSM everywhere else.
enum class SsaMethod { kExact, kAdaptive };
std::string_view to_string(SsaMethod method);

struct SsaSettings {
  JumpConvention convention = JumpConvention::kVolume;
  double regularization = 0.01;  ///< eps_h in r^2/(r^2 + eps_h h^2), >= 0
  SsaMethod method = SsaMethod::kExact;
  double tolerance = 0.01;  ///< kAdaptive only: 0 < eps < 1 (docs/method.md "Adaptive SSA")
};

// ---- the one set of range checks ------------------------------------------------------------
// Each records what it finds into `out` with fields relative to the object ("rate",
// "reactants[0].count"); references between objects (species names, regions) are the caller's.

void check(const Species& species, Problems& out);
void check(const Reaction& reaction, Problems& out);
void check(const SsaSettings& ssa, Problems& out);

/// The numbers of a reaction in any representation (by name here, by index in the services'
/// compiled forms): the rate, every stoichiometric count >= 1, mass action of order <= 2, and
/// a boundary flux's areas (a law, one finite area > 0 per site).
struct ReactionNumbers {
  double rate = 0.0;
  std::vector<long> reactant_counts;
  std::vector<long> product_counts;
  bool has_law = false;
  const std::vector<double>* areas = nullptr;  ///< boundary-flux areas, or null
  std::size_t sites = 0;                       ///< the particles they are parallel to
};
void check(const ReactionNumbers& reaction, Problems& out);

}  // namespace sadr::model
