// SPDX-License-Identifier: MIT
/// \file backend_schema.hpp
/// What each fluid backend is and takes, as data: its name, capabilities and a typed schema of
/// its `fluid.parameters`. The scene loader validates `fluid:` from it, the plan decides from it,
/// `sadr backends` prints it and docs/scene-format.md's backend tables are checked against it
/// (tests/fluid/backend_schema_test.cpp). Plain C++ (no numerics, no ZeroMQ, no protobuf), so
/// the orchestrator links it without the fluid code. Each backend's entry, `Backend
/// <name>_backend()`, lives in its own folder (`backends/<name>/<name>_schema.cpp`); the list is
/// SADR_FLUID_BACKENDS in fluid_service/backends/backends.cmake, from which CMake generates
/// `backends()` (`src/backend_list.cpp.in`).
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace sadr::fluid::schema {

/// One entry of `fluid.parameters`: a number, or a name among `choices` (the scene writes the
/// name; the loader sends its index, so the wire and the backend see the number k), or with
/// `file` a file the backend reads (the scene writes its path, relative to the scene file; the
/// loader checks that it opens and sends it absolute in FluidModel.files).
struct Parameter {
  std::string name;
  std::string unit;  ///< "dimensionless", "length", ... (docs/scene-format.md, units)
  double default_value = 0.0;
  double min = 0.0;  ///< allowed range [min, max] (+-inf: unbounded)
  double max = 0.0;
  bool whole = false;          ///< a whole number (flags, axes)
  bool open_interval = false;  ///< (min, max) instead of [min, max]
  std::string doc;             ///< one line
  /// Non-empty: the names of the values 0, 1, ... (then whole, min = 0, max = size - 1).
  std::vector<std::string> choices{};
  bool file = false;  ///< a file's path, not a number (unit, default, range unused)
  /// Whether v is allowed; else `why` says the range ("[0, 1]", "a whole number in [-1, 2]").
  [[nodiscard]] bool allows(double v, std::string& why) const;
  /// The index of the name `n` among choices, or -1.
  [[nodiscard]] int choice_index(std::string_view n) const;
};

struct Capabilities {
  bool moves_particles = false;          ///< positions evolve (else: the SSA graph is built once)
  bool transports_species = false;       ///< integrates deterministic species
  bool thermal_noise = false;            ///< honours fluid.temperature > 0
  bool open_boundaries = false;          ///< fluid.open_boundary
  std::vector<std::string> wall_models;  ///< fluid.wall_model values (first: the default)
  std::vector<std::string> kernels;      ///< fluid.kernel values (first: the default)
  /// Deterministic species terms on wall particles: reactions with `kinds` other than fluid,
  /// and the `free` boundary condition (wall particles that react and change). Without it the
  /// scene loader refuses them (they would be silently dropped).
  bool wall_species_terms = true;
  /// Deterministic boundary fluxes (scene `boundary_fluxes`: a law-valued source in the fluid
  /// particles next to a face). Without it the scene loader refuses them for deterministic
  /// species (stochastic ones are the SSA's and need nothing of the backend).
  bool boundary_fluxes = true;
  /// Wall particles with a prescribed velocity (scene: a wall fill rule's `velocity`, a solid
  /// body's `motion`): the backend holds it and its wall models use it; and bodies whose wall
  /// particles move (`motion: {moves: true}`, FluidModel::moving_bodies). Without it the scene
  /// loader refuses a moving wall (it would be held at rest) and the fluid core a moving body.
  bool moving_walls = false;
  /// Forces and torques on bodies (fluid.body_forces). Without it the scene loader and the
  /// fluid core refuse the key.
  bool body_forces = false;
};

/// Peak resident memory per particle with this backend (bench/memory_per_particle.py: the slope
/// between 1e5 and 4e5 particles, rounded up; docs/cli.md), for the run plan's memory estimate.
struct MemoryPerParticle {
  std::array<double, 3> fluid_service{710, 830, 900};  ///< [bytes] in 1D, 2D, 3D
  double sadr = 490;                                   ///< [bytes] the orchestrator's share
};

/// Wall time per particle and fluid sub-step with this backend [ns], at the fluid's default
/// threads on a 2-core machine (bench/cost_calibration.py: the median over the examples of
/// fluid compute time / (particles x sub-steps); docs/cli.md), for the plan's time estimate.
struct CostPerParticle {
  std::array<double, 3> substep_ns{200, 400, 1000};  ///< in 1D, 2D, 3D
};

struct Backend {
  std::string name;
  std::string summary;  ///< one line
  Capabilities capabilities;
  /// Scene keys of `fluid:` this backend needs (e.g. sound_speed). The scene loader chooses
  /// `sound_speed` from the flow when a scene leaves it out (docs/scene-format.md).
  std::vector<std::string> required;
  std::vector<Parameter> parameters;
  MemoryPerParticle memory{};
  CostPerParticle cost{};
  [[nodiscard]] const Parameter* parameter(std::string_view n) const;
  /// Whether `key` is in `required`.
  [[nodiscard]] bool needs(std::string_view key) const;
};

/// Every backend, by name (the registry's order; generated from SADR_FLUID_BACKENDS).
[[nodiscard]] const std::vector<Backend>& backends();
/// The backend called `name`, or nullptr.
[[nodiscard]] const Backend* find(std::string_view name);
/// The names joined by ", " (e.g. "prescribed, sdpd, static, tdpd").
[[nodiscard]] std::string names();
/// The parameter table of one backend as Markdown (the rows of docs/scene-format.md).
[[nodiscard]] std::string markdown_parameters(const Backend& b);
/// The capability table of all backends as Markdown.
[[nodiscard]] std::string markdown_capabilities();
/// `sadr backends`: every backend with its capabilities and parameters, plain text.
[[nodiscard]] std::string describe();

}  // namespace sadr::fluid::schema
