// SPDX-License-Identifier: MIT
/// \file scene_parts.hpp
/// (private) The pieces of the scene loader, one per section of the file.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sadr/orchestrator/scene.hpp"
#include "yaml_reader.hpp"

namespace sadr::orchestrator::detail {

struct MeshBody;  // scene_geometry_parts.hpp

/// State shared by the section readers during one load.
struct SceneContext {
  YamlReader& reader;
  Scene& scene;
  std::filesystem::path base_dir{};      ///< directory of the scene file (for relative paths)
  bool dimension_ok = false;             ///< `dimension` valid (vectors have that length)
  bool geometry_ok = false;              ///< dimension and box valid
  bool particles_ok = false;             ///< particles built and regions resolved
  std::optional<double> h_over_dx{};     ///< fluid.h_over_dx, resolved once dx is known
  Region all_region{};                   ///< the built-in region "all" (every particle)
  std::string particle_file_bytes{};     ///< the particle CSV file, folded into the scene hash
  std::optional<Field> boussinesq{};     ///< fluid.boussinesq, checked once species are known
  std::optional<Field> open_boundary{};  ///< fluid.open_boundary once its channel is read
  /// Regions of shape `ids` (index into scene.regions, their `ids` field),
  /// checked against the particle count once the particles exist.
  std::vector<std::pair<std::size_t, Field>> id_regions{};
  /// Particle CSV columns that are not particle properties (initial species
  /// values read by `count_column` / `concentration_column`), one value per
  /// particle; `used` is set by the species that read them.
  struct ExtraColumn {
    std::string name;
    std::vector<double> values;
    bool used = false;
  };
  std::vector<ExtraColumn> extra_columns{};
  std::string particle_file{};                 ///< the particle CSV's path (for messages)
  std::vector<int> particle_lines{};           ///< the CSV line of each particle
  std::optional<Field> particle_file_field{};  ///< particles.file
  /// Fluid and solid bodies of `geometry` whose shape is a mesh file, by body name.
  std::map<std::string, std::shared_ptr<const MeshBody>> mesh_bodies{};
  /// Absolute tolerance for region and box membership [length].
  [[nodiscard]] double tolerance() const;
};

inline constexpr std::string_view kAllRegion = "all";
/// Largest copy number a scene may give one particle: 2^53, the end of the
/// exact integer range of a double (the SSA counts in 64-bit integers).
inline constexpr double kMaxExactCount = 9007199254740992.0;

void read_regions(SceneContext& ctx, const Field& root);
void read_particles(SceneContext& ctx, const Field& root);
/// Top-level "geometry" (scene_geometry.cpp), instead of read_particles: particles from bodies.
void read_geometry(SceneContext& ctx, const Field& root);
void read_fluid(SceneContext& ctx, const Field& root);
/// Once the particles exist (scene_flow_scales.cpp): the sound speed a scene leaves out, and a
/// background pressure around a body in the flow, chosen from the flow's expected speed and
/// pressure variation (Scene::chosen says what and why); warnings where given values break the
/// rules. Backends without an equation of state: nothing.
void choose_flow_settings(SceneContext& ctx, const Field& root, bool sound_speed_given,
                          bool reference_density_given);
/// fluid.open_boundary against h and the particles (after read_particles).
void check_open_boundary(SceneContext& ctx);
/// fluid.wall_planes name regions of the scene (after read_regions).
void check_wall_planes(SceneContext& ctx, const Field& root);
/// fluid.body_forces (scene_body_forces.cpp): regions holding wall particles (after the
/// particles and regions).
void check_body_forces(SceneContext& ctx, const Field& root);
void read_species(SceneContext& ctx, const Field& root);
void read_reactions(SceneContext& ctx, const Field& root);
/// A boundary flux's `surface: name` (and `group`, `region`; scene_flux_surfaces.cpp): sets the
/// reaction's boundary particles and areas, or says why not and returns false.
bool read_surface_share(SceneContext& ctx, const Field& f, const Field& root,
                        const std::string& name, Reaction& rx);
/// A species boundary's `surface: BODY` (with `group`; scene_surface_groups.cpp): the wall
/// particles behind BODY's surface (every wall layer), or behind the part of it that a physical
/// group of its mesh file covers, ascending; nullopt, with an error at file:line, when there is
/// none or the keys are wrong.
std::optional<std::vector<std::uint32_t>> surface_walls(SceneContext& ctx, const Field& f,
                                                        const Field& root);
/// Top-level "boundary_fluxes" (scene_fluxes.cpp), after read_reactions: each one a reaction
/// with a law and its boundary particles and areas.
void read_boundary_fluxes(SceneContext& ctx, const Field& root);
/// After the particles are made: refuses id-listed regions beyond them and resolves every
/// region's membership (scene_lattice.cpp; the lattice, a particle file and geometry).
void resolve_regions(SceneContext& ctx, const ParticleState& particles);
/// Checks the species of a reaction (declared, one path); returns whether they are
/// stochastic (nullopt if unknown or mixed; reported at `where`).
std::optional<bool> check_reaction_species(SceneContext& ctx, const Field& where,
                                           const Reaction& rx);
/// Top-level "parameters" (scene_laws.cpp): named constants of rate laws.
void read_parameters(SceneContext& ctx, const Field& root);
/// Reports parameters that have the name of a species (after read_species).
void check_parameter_names(SceneContext& ctx, const Field& root);
/// The reaction's "law" into rx.law, compiled and sampled at admissible states;
/// false if absent. Needs rx's species checked and rx.stochastic set.
bool read_law(SceneContext& ctx, const Field& reaction, Reaction& rx);
/// A species entry with `assigned` into scene.assigned (checked by check_assigned).
void read_assigned(SceneContext& ctx, const Field& entry);
/// Expands and compiles every assigned species' expression (after read_species).
void check_assigned(SceneContext& ctx, const Field& root);
void read_time_and_output(SceneContext& ctx, const Field& root);
/// time.tolerance (a number: relative; or {relative, absolute, max_step}), after
/// time.coupling_step was read (scene_tolerance.cpp).
void read_time_tolerance(SceneContext& ctx, const Field& time);

// Silent zeros (scene_warnings.cpp): warnings with the key and line.
/// A reaction whose regions and kinds select no particle.
void warn_reaction_selects_nothing(SceneContext& ctx, const Field& f, const Reaction& rx);
/// Molecules that start on wall particles without a boundary condition for their species.
/// A stochastic species with a `dirichlet` boundary whose other wall particles have no
/// dirichlet or free condition: the SSA makes them absorbing reservoirs (C = 0).
void warn_absorbing_walls(SceneContext& ctx, const Field& f, const Species& sp);
void warn_inert_wall_molecules(SceneContext& ctx, const Field& f, const Species& sp);
/// A stochastic initial concentration that rounds to 0 molecules in every particle.
void warn_rounds_to_zero(SceneContext& ctx, const Field& value_field, const Species& sp,
                         const Region& rg, double concentration);
/// Species that stay zero (nothing starts, holds or produces them), and dirichlet reservoirs
/// that cannot diffuse (after the reactions and boundary fluxes are read).
void warn_species_never_present(SceneContext& ctx, const Field& root);
/// Observables over regions that stay empty (a backend that does not move particles).
void warn_empty_observables(SceneContext& ctx, const Field& root);

/// Parses "fluid", "wall", "inlet", "outlet" (nullopt otherwise).
std::optional<ParticleKind> parse_kind(std::string_view name);
/// Why `name` cannot be a scene name (it names output files), or nullopt.
std::optional<std::string> invalid_scene_name(std::string_view name);
/// The default scene name: the file's stem, other characters replaced by '_'.
std::string scene_name_from_file(const std::filesystem::path& source);
/// True for [A-Za-z_][A-Za-z0-9_]*.
bool valid_identifier(std::string_view name);
/// The region named `name` ("all" included), reporting an unknown name with
/// the nearest known one; nullptr if unknown.
const Region* lookup_region(SceneContext& ctx, const Field& where, const std::string& name);

}  // namespace sadr::orchestrator::detail
