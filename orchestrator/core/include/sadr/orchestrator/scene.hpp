// SPDX-License-Identifier: MIT
/// \file scene.hpp
/// The validated, fully resolved content of a scene file: the particles, the
/// named regions resolved to particle indices, the fluid model, the chemistry,
/// the time stepping, the output schedule and the seed. Everything the fluid
/// and SSA services need (FluidModel, SsaModel, Species, Reaction,
/// WallBoundary, RegionMembership in proto/sadr/.../v1) is here, in plain C++
/// types; the conversion to protobuf lives outside this library.
///
/// Units: one consistent system chosen by the scene author (SI or reduced);
/// "d" is the dimension. docs/scene-format.md documents every key.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "sadr/common/particle_state.hpp"
#include "sadr/common/rate_law.hpp"
#include "sadr/model/chemistry.hpp"
#include "sadr/model/fluid.hpp"
#include "sadr/orchestrator/output_settings.hpp"
#include "sadr/orchestrator/region.hpp"

namespace sadr::orchestrator {

using model::BoundaryCondition;
using model::SpeciesBoundary;
using model::to_string;

/// A species of the scene: the model's species and its initial values.
struct Species : model::Species {
  /// Initial value per particle (size N): copy numbers [molecules] (whole
  /// numbers) for a stochastic species, concentrations [molecules/length^d]
  /// for a deterministic one. Dirichlet particles already hold their value.
  std::vector<double> initial;
};

/// A species given by an expression of the others' concentrations (an SBML
/// assignment rule, scene key `assigned`): evaluated where frames are
/// written, as a concentration; never integrated, transported or sent to a
/// service. Rate-law expressions that name it read its expression.
struct AssignedSpecies {
  std::string name;
  std::string expression;  ///< as written
  std::string expanded;    ///< other assigned species substituted, parenthesised
  std::string origin;      ///< "file:line", for messages
};

using model::Reaction;
using model::StoichiometryEntry;

using model::Boussinesq;
using model::FluidSettings;
using model::OpenBoundarySettings;
using model::WallPlane;

enum class Splitting { kLie, kStrang };
std::string_view to_string(Splitting splitting);

struct TimeSettings {
  double coupling_step = 0.0;  ///< tau > 0 [time]
  double end = 0.0;            ///< end time >= 0 [time]; the run starts at 0
  Splitting splitting = Splitting::kLie;
};

using model::JumpConvention;
using model::SsaSettings;

/// A loaded, validated scene. Build it with load_scene() or parse_scene().
struct Scene {
  std::string name;
  std::string description;
  std::filesystem::path source_path;  ///< the file it came from ("" for text)
  /// "fnv1a64:<16 hex>" of the scene file bytes, followed by the bytes of
  /// the particle CSV file when the scene reads one.
  std::string source_hash;
  /// Overrides applied to the file ("PATH=VALUE", in order; scene_override.hpp).
  /// With overrides, source_hash covers them too: the hash of the effective scene.
  std::vector<std::string> overrides;
  Box box;
  double lattice_spacing = 0.0;  ///< dx [length]; 0 when the particles came from a file
  ParticleState particles;       ///< ids = 0..N-1, velocities present
  std::vector<Region> regions;   ///< named regions with resolved membership
  FluidSettings fluid;
  std::map<std::string, double> parameters;  ///< named constants of rate laws
  std::vector<Species> species;
  std::vector<AssignedSpecies> assigned;  ///< not in `species`: no service sees them
  std::vector<Reaction> reactions;
  TimeSettings time;
  OutputSettings output;
  SsaSettings ssa;
  std::uint64_t seed = 0;
  /// What the loader found valid but very likely not meant ("file:line:col: field: message",
  /// in file order): a term that selects no particle, molecules that never reach the fluid.
  /// Not part of the scene's meaning (nor of its hash); `sadr validate --strict` refuses them.
  std::vector<std::string> warnings;

  [[nodiscard]] const Species* find_species(std::string_view name) const;
  [[nodiscard]] const AssignedSpecies* find_assigned(std::string_view name) const;
  [[nodiscard]] const Region* find_region(std::string_view name) const;
  [[nodiscard]] std::size_t stochastic_species_count() const;
  [[nodiscard]] std::size_t deterministic_species_count() const;
};

}  // namespace sadr::orchestrator
