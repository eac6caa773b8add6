// SPDX-License-Identifier: MIT
/// \file run_health.hpp
/// Whether the fluid and the chemistry of a run stayed sound, from its frames (the health
/// section of `sadr summary`, docs/cli.md "Health"):
///  - fluid particles inside walls: past a wall surface of fluid.wall_planes (a plane counts only
///    within h of a wall particle of its region), or, for wall particles without a surface,
///    closer than half a lattice spacing to one (the lattice fill puts the wall surface half a
///    spacing in front of the first wall layer, so such a particle is past it); with Morris
///    walls made by the geometry (scene_wall_tangents; a turning body's turned to the frame's
///    time), past the tangent plane of the wall particle within h whose closest surface point is
///    nearest, by more than kHealthTangentSlack dx (the plane departs from a curved surface by
///    about dx^2 / (4 R));
///  - empty holes: connected empty cells of a grid of cell size >= h (the kernel support) that do
///    not reach the edge of the particles' extent and that mostly border cells holding fluid;
///  - the density deviation |rho/rho0 - 1| over fluid particles (max and RMS);
///  - per species, the totals at the first and last frame with the reactions and boundaries
///    that can change them: a change of a species nothing can change is reported.
/// Each check has a WARNING threshold (the constants below).
#pragma once

#include <nlohmann/json.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "sadr/common/particle_state.hpp"
#include "sadr/common/rigid_motion.hpp"
#include "sadr/common/wall_surface.hpp"
#include "sadr/orchestrator/frame_writers.hpp"

namespace sadr::orchestrator {

struct Scene;

/// WARNING: a fluid particle is inside a wall at some checked frame.
inline constexpr std::size_t kHealthPenetrationWarn = 1;
/// Morris walls made by the geometry: a fluid particle counts as inside a wall when it lies
/// past its wall particle's tangent plane by more than this many lattice spacings.
inline constexpr double kHealthTangentSlack = 0.1;
/// WARNING: an empty hole at some checked frame.
inline constexpr std::size_t kHealthHoleWarn = 1;
/// WARNING: max |rho/rho0 - 1| over fluid particles and checked frames above this.
inline constexpr double kHealthDensityMaxWarn = 0.10;
/// WARNING: the RMS of rho/rho0 - 1 over the fluid particles of a frame above this.
inline constexpr double kHealthDensityRmsWarn = 0.03;
/// WARNING: a deterministic species nothing can change changed by more than this relative
/// amount (a stochastic one: by any molecule).
inline constexpr double kHealthAmountRelWarn = 1e-6;

/// What the checks need to know of the scene.
struct HealthContext {
  /// Dimension and periodic axes (non-periodic: lo/hi unused); without the scene
  /// (from_scene false) no axis is periodic and the dimension is taken from the first frame.
  Box box;
  double spacing = 0;            ///< lattice spacing dx [length]; 0 = estimate from a frame
  double support = 0;            ///< kernel support h [length]; 0 = 2 dx
  double reference_density = 0;  ///< fluid.reference_density (shown); 0 = unknown
  /// rho0 of the density check: the median fluid density of the first frame (set by the first
  /// HealthCheck::add_frame), the density the fluid was set up at; fluid.reference_density may lie
  /// below it on purpose (a background pressure). 0 = not yet known.
  double rest_density = 0;
  bool from_scene = false;  ///< the values above came from the run's scene
  struct Surface {
    std::string region;
    WallSurface surface;
    std::vector<std::uint64_t> wall_ids;  ///< ids of the region's wall particles
  };
  std::vector<Surface> surfaces;  ///< fluid.wall_planes
  /// Morris walls made by the geometry: the wall particles' tangent planes, by particle id.
  WallTangents tangents;
  /// Bodies that turn (motion: {moves: true} with an angular velocity): per entry of `tangents`
  /// the index into `turning` (-1: at rest or only translating), whose rotation at a frame's time
  /// turns the entry's normal (the normals above are those at t = 0). Empty: none.
  std::vector<int> tangent_turns;
  std::vector<RigidMotion> turning;
  /// Per species of the scene: what can change its total.
  struct SpeciesInfo {
    std::string name;
    bool stochastic = true;
    std::vector<std::string> reactions;   ///< reactions whose net stoichiometry changes it
    std::vector<std::string> boundaries;  ///< "region: condition" that create or remove it
  };
  std::vector<SpeciesInfo> species;
  bool species_known = false;  ///< `species` is the scene's (else unknown)
};

/// The context of a loaded scene: box, dx, h, rho0, wall_planes, species with the reactions
/// and boundaries (dirichlet, neumann, inflow, the open boundary) that change their totals.
HealthContext health_context(const Scene& scene);

/// A particle a check points at.
struct HealthPlace {
  std::uint64_t id = 0;
  std::array<double, 3> x{};
  double time = 0;
  std::string frame;  ///< the frame file
  double value = 0;   ///< depth [length], deviation, ...
  bool found = false;
};

struct PenetrationResult {
  std::size_t count = 0;  ///< fluid particles inside a wall
  HealthPlace worst;      ///< the deepest (value: depth past the surface [length])
};
/// Fluid particles of `p` (positions 3 per particle) inside walls. Needs spacing > 0.
PenetrationResult find_wall_penetration(const ParticleState& p, const HealthContext& c);

struct HoleResult {
  std::size_t count = 0;    ///< empty holes
  double cell = 0;          ///< grid cell size [length]
  std::size_t largest = 0;  ///< empty cells of the largest hole
  std::array<double, 3> centre{};
  bool checked = true;  ///< false: the grid would be too large (over 2^26 cells)
};
/// Empty holes among the particles of `p`: with cell size s >= h (periodic axes: L / floor(L /
/// h)), a connected set (by faces) of empty cells that touches no edge of the grid (the particles'
/// bounding box on a non-periodic axis) and whose bordering cells hold a fluid particle in at
/// least half of the cases. A lattice of spacing <= h leaves no cell empty.
HoleResult find_holes(const ParticleState& p, const HealthContext& c);

struct DensityResult {
  std::size_t fluid = 0;  ///< fluid particles
  double max = 0;         ///< max |rho/rho0 - 1|
  double rms = 0;         ///< sqrt(mean (rho/rho0 - 1)^2)
  std::uint64_t max_id = 0;
  std::array<double, 3> max_x{};
};
DensityResult density_deviation(const ParticleState& p, double reference_density);

/// Median distance to the nearest other particle (an estimate of dx), 0 for < 2 particles.
double estimate_spacing(const ParticleState& p, const Box& box);

/// Per species: the totals at the first and last frame and what can change them.
struct SpeciesBudget {
  std::string name;
  bool amount = false;  ///< deterministic: sum c_i V_i (else the sum of copy numbers)
  double first = 0, last = 0;
  double first_time = 0, last_time = 0;
  std::vector<std::string> reactions, boundaries;
  bool known = false;  ///< reactions/boundaries are the scene's
  /// "conserved" (nothing changes it), "boundaries" (only boundaries: the change is theirs),
  /// "reactions" (only reactions), "both" (reactions and boundaries: not separable from
  /// frames), "unknown" (no scene)
  std::string verdict;
  bool warning = false;  ///< conserved, but changed
};

/// The health of one run or of several (an ensemble's realizations), frame by frame.
class HealthCheck {
 public:
  explicit HealthCheck(HealthContext context) : c_(std::move(context)) {}
  /// Adds one frame of run `run` (0, 1, ...: frames of one run in time order).
  void add_frame(const ParticleState& p, std::span<const SpeciesColumn> species, double time,
                 const std::string& frame, std::size_t run = 0);
  /// Fills the budgets (after the last frame) and returns the report as JSON:
  /// {"context", "penetration", "holes", "density", "species", "warnings"}.
  [[nodiscard]] nlohmann::json report() const;
  /// The human-readable lines (indented, "WARNING: ..." lines included).
  [[nodiscard]] std::vector<std::string> lines() const;
  [[nodiscard]] std::vector<std::string> warnings() const;
  [[nodiscard]] const HealthContext& context() const { return c_; }
  [[nodiscard]] std::size_t frames() const { return frames_; }

  // Results so far (over the frames added).
  std::size_t penetration_frames = 0;  ///< frames with a fluid particle inside a wall
  std::size_t penetration_max = 0;     ///< most such particles in one frame
  double penetration_max_time = 0;
  std::size_t penetration_last = 0;  ///< at the last frame added
  HealthPlace penetration_worst;
  std::size_t hole_frames = 0;  ///< frames with a hole
  std::size_t holes_max = 0;    ///< most holes in one frame
  double holes_max_time = 0;
  std::size_t holes_last = 0;
  bool holes_checked = true;
  double hole_cell = 0;
  std::size_t hole_largest = 0;  ///< cells of the largest hole
  HealthPlace hole_worst;        ///< its centre (id unused)
  HealthPlace density_worst;     ///< value: |rho/rho0 - 1|
  double density_rms_max = 0;
  double density_rms_max_time = 0;
  double density_rms_last = 0;
  std::vector<SpeciesBudget> budgets() const;

 private:
  HealthContext c_;
  std::size_t frames_ = 0;
  struct RunTotals {
    std::vector<std::string> names;
    std::vector<double> first, last;
    double first_time = 0, last_time = 0;
    bool any = false;
  };
  std::vector<RunTotals> runs_;
};

}  // namespace sadr::orchestrator
