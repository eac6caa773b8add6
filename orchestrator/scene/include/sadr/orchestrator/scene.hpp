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
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sadr/common/particle_state.hpp"
#include "sadr/common/rate_law.hpp"
#include "sadr/common/rigid_motion.hpp"
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

/// time.tolerance: the coupling step chosen by an error controller (docs/method.md section 1b).
struct StepTolerance {
  double relative = 0.0;  ///< >= 0, of the RMS over particles of each coupling input
  double absolute = 0.0;  ///< >= 0, in the input's units (molecules, concentration)
  double max_step = 0.0;  ///< largest step [time]; >= coupling_step (the first step)
};

struct TimeSettings {
  double coupling_step = 0.0;  ///< tau > 0 [time]; with `tolerance`, the first step
  double end = 0.0;            ///< end time >= 0 [time]; the run starts at 0
  Splitting splitting = Splitting::kLie;
  std::optional<StepTolerance> tolerance;  ///< none: every step is coupling_step
};

using model::JumpConvention;
using model::SsaSettings;

/// What the scene's `geometry` section made (docs/scene-format.md, "geometry"): per particle the
/// surface it belongs to, and the figures `sadr geometry` prints. Regions the section defines are
/// ordinary entries of Scene::regions (shape `ids`, membership resolved).
struct GeometryBody {
  std::string name;
  std::string role;                      ///< "fluid", "solid" or "region"
  int surface_id = -1;                   ///< fluid and solid bodies: the id their walls carry
  std::string origin;                    ///< "file:line" of the body
  std::optional<double> exact_volume{};  ///< of the shape (area in 2D), where a formula exists
  /// Area of the shape's surface (perimeter in 2D) where the shape gives it (Shape::exact_area).
  std::optional<double> exact_area{};
  bool inside_box = false;  ///< the shape's bounds lie inside the box (no surface is cut off)
  /// Solid bodies with `motion: {moves: true}`: the rigid motion their wall particles follow
  /// (the region `name` holds them); unset: their walls stay in place.
  std::optional<RigidMotion> moving{};
};

struct GeometryReport {
  std::string lattice;      ///< "cubic" or "hexagonal"
  double spacing = 0.0;     ///< dx [length]
  double wall_depth = 0.0;  ///< wall layer depth behind each surface [length]
  std::vector<GeometryBody> bodies;
  /// Per particle: the surface id (GeometryBody::surface_id) behind which a wall particle sits,
  /// or the nearest one within wall_depth + spacing of a fluid particle; -1 if none.
  std::vector<int> surface_id;
  /// Per particle: depth behind the surface (walls) or distance to it (fluid), +inf if none.
  std::vector<double> surface_distance;
  /// Per particle: the unit normal of a wall particle's surface pointing into the fluid (its
  /// closest surface point is x + surface_distance * normal); (0, 0, 0) for fluid particles.
  std::vector<std::array<double, 3>> surface_normal;
  /// Per particle: n_i / n_ref - 1 after relaxation (Wendland C2 number density against the
  /// ideal lattice's); empty when the section does not relax.
  std::vector<double> density_error;
  bool relaxed = false;
  int relax_iterations = 0;
  double max_error_before = 0.0, rms_error_before = 0.0;  ///< over fluid particles
  double max_error = 0.0, rms_error = 0.0;
  double fluid_volume = 0.0;                 ///< the fluid particles' volumes summed [length^d]
  double lattice_fluid_volume = 0.0;         ///< N_fluid dx^d [length^d]
  std::optional<double> exact_fluid_volume;  ///< where the shapes give it
  /// Thinnest feature found (fluid gap or solid, measured along surface normals) [length]:
  /// +inf when none is thinner than `feature_search` [length].
  double smallest_feature = std::numeric_limits<double>::infinity();
  std::string smallest_feature_where;  ///< "body 'x' near (x, y, z)"
  double feature_search = 0.0;
  std::vector<std::string> notes;  ///< what was handled on the way (flipped mesh normals)
};

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
  /// Settings the loader chose for keys the scene leaves out (the sound speed, a background
  /// pressure), each with its reason; the plan prints them.
  std::vector<std::string> chosen;
  /// Set when the particles came from the `geometry` section (shared: scenes are copied).
  std::shared_ptr<const GeometryReport> geometry;

  [[nodiscard]] const Species* find_species(std::string_view name) const;
  [[nodiscard]] const AssignedSpecies* find_assigned(std::string_view name) const;
  [[nodiscard]] const Region* find_region(std::string_view name) const;
  [[nodiscard]] std::size_t stochastic_species_count() const;
  [[nodiscard]] std::size_t deterministic_species_count() const;
};

}  // namespace sadr::orchestrator
