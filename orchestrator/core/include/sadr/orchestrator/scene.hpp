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
#include "sadr/orchestrator/frame_writers.hpp"
#include "sadr/orchestrator/region.hpp"

namespace sadr::orchestrator {

/// Per-species condition on the non-fluid particles of one region.
/// The first three match sadr.common.v1.WallCondition.
enum class BoundaryCondition {
  kNone,       ///< no-flux: the wall particles take no part for this species
  kDirichlet,  ///< the particles are reservoirs held at `value` [molecules/length^d]
  kNeumann,    ///< inward flux density `value` [molecules/(length^(d-1) time)]
  kFree,       ///< the particles exchange molecules like fluid particles but do not move
               ///< (needs WALL_CONDITION support on the wire; see docs/scene-format.md)
  kInflow,     ///< the particles inside the region's box or channel (any kind,
               ///< re-evaluated as they move) are reset to `value`: stochastic species
               ///< at the start of every SSA step, deterministic ones after every fluid
               ///< call (an inlet buffer)
};
std::string_view to_string(BoundaryCondition condition);

struct SpeciesBoundary {
  std::string region;  ///< region name (its particles are all non-fluid, except for kInflow)
  BoundaryCondition condition = BoundaryCondition::kNone;
  double value = 0.0;  ///< see BoundaryCondition
};

struct Species {
  std::string name;          ///< [A-Za-z_][A-Za-z0-9_]*, unique
  bool stochastic = true;    ///< integer copy numbers (ssa_service) or concentrations (fluid)
  double diffusivity = 0.0;  ///< kappa >= 0 [length^2/time]
  std::vector<SpeciesBoundary> boundaries;
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

struct StoichiometryEntry {
  std::string species;
  std::uint32_t count = 1;  ///< >= 1
  bool operator==(const StoichiometryEntry&) const = default;
};

/// One irreversible reaction ("A + B -> C"); reversible ones in the file
/// become two of these ("name" and "name_reverse"). Mass action (`rate`) or
/// another rate law (`law`, common/rate_law.hpp).
struct Reaction {
  std::string name;
  std::vector<StoichiometryEntry> reactants;  ///< total order <= 2 for mass action
  std::vector<StoichiometryEntry> products;
  /// Rate constant in concentration units: order 0 [molecules/(length^d time)],
  /// order 1 [1/time], order 2 [length^d/(molecules time)], A + A defined by
  /// dC/dt = -k C^2 (docs/scene-format.md).
  double rate = 0.0;
  std::vector<ParticleKind> kinds;   ///< where it may fire; default {fluid}
  std::vector<std::string> regions;  ///< empty = everywhere
  bool stochastic = true;            ///< among stochastic species (SSA) or deterministic (fluid)
  /// A law other than mass action (scene key `law`); `rate` is then unused.
  /// Assigned species are already substituted into an expression.
  std::optional<rate_law::Definition> law{};
  /// Hybrid reaction (docs/method.md section 4c): the species of the other path its
  /// law reads (a stochastic reaction: deterministic species, frozen over each SSA
  /// stage; a deterministic one: stochastic species, as X / V from the back-transfer).
  std::vector<std::string> reads_other{};
  bool uses_time = false;  ///< the law reads the time t
  /// Non-empty: a boundary flux (scene `boundary_fluxes`): the law is a flux density j
  /// [molecules/(length^(d-1) time)] into the fluid, fired only in these fluid particles, each
  /// with its share of the face's area [length^(d-1)] (boundary_share.hpp); `regions` empty.
  std::vector<std::uint32_t> boundary_particles{};
  std::vector<double> boundary_areas{};
  [[nodiscard]] unsigned order() const;
};

/// Boussinesq body force g_b beta (C_s - C_ref) along `direction`.
struct Boussinesq {
  std::string species;
  double coefficient = 0.0;                        ///< g_b * beta [length^(d+2)/(time^2 molecules)]
  double reference = 0.0;                          ///< C_ref [molecules/length^d]
  std::array<double, 3> direction{0.0, 1.0, 0.0};  ///< unit vector
};

/// The wall surface of a region of wall particles (fluid.wall_planes; Morris walls): a plane,
/// or with radius > 0 a circle (2D) / sphere (3D) around `point` with the fluid outside.
struct WallPlane {
  std::string region;
  std::array<double, 3> point{};   ///< a point on the plane, or the centre [length]
  std::array<double, 3> normal{};  ///< plane: unit normal from the wall into the fluid
  double radius = 0.0;             ///< > 0: circle / sphere of this radius [length]
};

/// fluid.open_boundary (sdpd): an open channel along `axis` (docs/scene-format.md). Inlet buffer
/// [inlet_lo, fluid_lo), fluid [fluid_lo, fluid_hi), outlet buffer [fluid_hi, outlet_hi].
struct OpenBoundarySettings {
  int axis = 0;
  double inlet_lo = 0, fluid_lo = 0, fluid_hi = 0, outlet_hi = 0;  ///< [length]
  bool parabolic = false;           ///< profile: parabolic (else uniform)
  double mean_velocity = 0;         ///< mean inflow speed along +axis [length/time]
  int cross_axis = 1;               ///< parabolic: the axis across the channel
  double wall_lo = 0, wall_hi = 0;  ///< parabolic: its no-slip planes [length]
};

struct FluidSettings {
  std::string backend = "sdpd";   ///< "sdpd", "static" or "tdpd"
  double smoothing_length = 0.0;  ///< h [length]
  std::string kernel = "lucy";
  double reference_density = 1.0;           ///< rho_0 [mass/length^d]
  double sound_speed = 0.0;                 ///< c_0 [length/time] (sdpd)
  double shear_viscosity = 0.0;             ///< eta [mass/(length^(d-2) time)]
  double temperature = 0.0;                 ///< k_B T [energy]; 0 = no thermal noise
  std::array<double, 3> gravity{};          ///< body force per mass [length/time^2]
  std::string density_mode = "continuity";  ///< "continuity" or "summation"
  std::optional<Boussinesq> boussinesq;
  double max_time_step = 0.0;  ///< upper bound on the fluid sub-step [time]; 0 = none
  bool force_time_step = false;
  std::map<std::string, double> parameters;  ///< backend-specific numbers
  std::map<std::string, std::string> files;  ///< backend-specific files: absolute paths
  std::string wall_model = "stationary";     ///< one of the backend's wall models
  std::vector<WallPlane> wall_planes;        ///< wall_model "morris": one per wall region
  std::optional<OpenBoundarySettings> open_boundary;
};

enum class Splitting { kLie, kStrang };
std::string_view to_string(Splitting splitting);

struct TimeSettings {
  double coupling_step = 0.0;  ///< tau > 0 [time]
  double end = 0.0;            ///< end time >= 0 [time]; the run starts at 0
  Splitting splitting = Splitting::kLie;
};

enum class OutputFormat { kVtu, kVtp, kCsv };
std::string_view to_string(OutputFormat format);

/// A scalar the scene names for the sweep's observables.csv (output.observables):
/// per frame, the sum (`mean` false) or the mean over the particles of `region`
/// (at that frame's positions) of the species column `species`.
struct ObservableSpec {
  std::string name;
  std::string species;
  std::string region = "all";
  bool mean = false;
};

struct OutputSettings {
  std::string directory;      ///< "" = chosen by the CLI
  std::vector<double> times;  ///< sorted, unique, in [0, end], always ends with `end` [time]
  std::vector<OutputFormat> formats{OutputFormat::kVtu, OutputFormat::kCsv};
  std::vector<std::string> species;  ///< species written per frame (default all)
  double checkpoint_every = 0.0;     ///< simulated time between checkpoints; 0 = only on signal
  VtkEncoding vtk_encoding = VtkEncoding::kBinary;  ///< .vtu/.vtp array storage
  std::vector<ObservableSpec> observables;          ///< named scalars (sweeps)
};

enum class JumpConvention { kSymmetric, kVolume };
std::string_view to_string(JumpConvention convention);

struct SsaSettings {
  JumpConvention convention =
      JumpConvention::kVolume;   ///< same default as ssa_service (NOTATION.md)
  double regularization = 0.01;  ///< eps_h in r^2/(r^2 + eps_h h^2), >= 0
};

/// What the scene's `geometry` section made (docs/scene-format.md, "geometry"): per particle the
/// surface it belongs to, and the figures `sadr geometry` prints. Regions the section defines are
/// ordinary entries of Scene::regions (shape `ids`, membership resolved).
struct GeometryBody {
  std::string name;
  std::string role;                      ///< "fluid", "solid" or "region"
  int surface_id = -1;                   ///< fluid and solid bodies: the id their walls carry
  std::string origin;                    ///< "file:line" of the body
  std::optional<double> exact_volume{};  ///< of the shape (area in 2D), where a formula exists
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
  /// Set when the particles came from the `geometry` section (shared: scenes are copied).
  std::shared_ptr<const GeometryReport> geometry;

  [[nodiscard]] const Species* find_species(std::string_view name) const;
  [[nodiscard]] const AssignedSpecies* find_assigned(std::string_view name) const;
  [[nodiscard]] const Region* find_region(std::string_view name) const;
  [[nodiscard]] std::size_t stochastic_species_count() const;
  [[nodiscard]] std::size_t deterministic_species_count() const;
};

}  // namespace sadr::orchestrator
