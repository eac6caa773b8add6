// SPDX-License-Identifier: MIT
/// \file particles.hpp
/// Particles from geometry (docs/geometry.md): lattice fill of a fluid domain (a body minus solid
/// bodies, inside a box), wall particles in layers behind every solid surface and the body's own
/// boundary, each knowing its surface; an optional relaxation that evens out the SPH density;
/// volumes and masses summing to the domain volume.
#pragma once

#include <array>
#include <optional>
#include <utility>
#include <vector>

#include "sadr/geometry/shape.hpp"

namespace sadr::geometry {

/// kCubic: square (2D) / simple cubic (3D). kHexagonal: hexagonal (2D) / face-centred cubic, the
/// close packing (3D). Both give one particle per spacing^d of volume, so a lattice choice does
/// not change the particle count or mass; the nearest-neighbour distance is spacing on the cubic
/// lattice, (2/sqrt 3)^(1/2) spacing = 1.075 spacing on the hexagonal one and 2^(1/6) spacing =
/// 1.122 spacing on the FCC one.
enum class Lattice { kCubic, kHexagonal };

struct SolidBody {
  ShapePtr shape;
  int surface_id = 1;  ///< carried by its wall particles
};

struct FluidDomain {
  int dimension = 3;
  Aabb box;                                           ///< particles live in [lo, hi)
  std::array<bool, 3> periodic{false, false, false};  ///< used by relax()
  ShapePtr body;                                      ///< null: the whole box is the body
  int body_surface_id = 0;                            ///< of the wall layer outside `body`
  std::vector<SolidBody> solids;
};

struct FillOptions {
  double spacing = 0;  ///< particle spacing dx (volume dx^d per particle) [length]
  Lattice lattice = Lattice::kCubic;
  double wall_depth = 0;  ///< wall layer thickness behind every surface, e.g. the kernel support
  Vec3 offset{};          ///< lattice shift (fractions of spacing) from the box's lower corner
  int threads = 0;        ///< 0: hardware concurrency
};

enum class Kind : unsigned char { kFluid = 0, kWall = 1 };

/// Struct of arrays, one entry per particle.
struct ParticleSet {
  int dimension = 3;
  double spacing = 0;
  std::vector<Vec3> position;
  std::vector<Kind> kind;
  /// Wall particles: the surface behind which they sit (SolidBody::surface_id or
  /// FluidDomain::body_surface_id). Fluid particles: the nearest surface if it lies within
  /// wall_depth + spacing (so "the fluid next to surface s" is kind == fluid, surface_id == s,
  /// distance < spacing), else -1.
  std::vector<int> surface_id;
  /// Wall particles: depth behind their surface (>= 0, the shape's distance, see shape.hpp);
  /// fluid particles: distance to the nearest surface (>= 0), or +inf if none within
  /// wall_depth + spacing (relax() updates it for the particles it moves).
  std::vector<double> distance;
  /// Wall particles: unit normal of their surface pointing into the fluid; fluid: (0, 0, 0).
  std::vector<Vec3> normal;
  /// Volume [length^d]: spacing^d after fill(); set by assign_volumes().
  std::vector<double> volume;
  /// Mass [mass]: rest_density * volume (fill() uses rest density 1; assign_volumes() sets it).
  std::vector<double> mass;

  [[nodiscard]] std::size_t size() const { return position.size(); }
  [[nodiscard]] std::size_t count(Kind k) const;
};

/// Distance from the fluid point x to the nearest surface of the fluid region (the body's or a
/// solid's) and that surface's id, when within `limit`; else (+inf, -1).
std::pair<double, int> nearest_surface(const FluidDomain& domain, Vec3 x, double limit);

/// Signed distance to the fluid region's boundary: max(body, -solid_1, -solid_2, ...),
/// negative in the fluid (the box's faces do not count). Same contract as Shape.
double fluid_signed_distance(const FluidDomain& domain, Vec3 p);

/// Lattice sites of the box: fluid where inside the body and outside every solid; wall where not
/// fluid and within wall_depth behind a solid's surface or outside the body's, with at least one
/// fluid particle within wall_depth (walls that no fluid sees are dropped). Sites are culled in
/// blocks by the shapes' distance bound, so most of the box costs one query per block.
ParticleSet fill(const FluidDomain& domain, const FillOptions& options);

struct RelaxOptions {
  double support = 0;  ///< kernel support radius h (Wendland C2) [length]
  int max_iterations = 400;
  double tolerance = 0.01;  ///< stop when max |rho / rho_ref - 1| over fluid particles < this
  double max_step = 0.2;    ///< largest move per iteration [spacing]
  int threads = 0;
};

struct RelaxReport {
  int iterations = 0;
  double max_error_before = 0, rms_error_before = 0;  ///< |n_i / n_ref - 1| over fluid
  double max_error = 0, rms_error = 0;
  double reference_number_density = 0;  ///< n_ref: the kernel sum of the ideal lattice [1/L^d]
  double seconds = 0;
};

/// SPH number densities n_i = sum_j W(|x_i - x_j|) (j over all particles, i included; periodic
/// axes by minimum image) of every particle, and the reference n_ref of the ideal lattice.
std::vector<double> number_density(const ParticleSet& particles, const FluidDomain& domain,
                                   double support, int threads = 0);
double reference_number_density(int dimension, Lattice lattice, double spacing, double support);

/// Moves the fluid particles (walls stay on the lattice) to minimise sum_i (n_i / n_ref - 1)^2 over
/// the fluid, by Gauss-Newton-scaled gradient steps with a line search, keeping them in the fluid
/// region by the signed distance (src/relax.cpp); returns the density error before and after.
RelaxReport relax(ParticleSet& particles, const FluidDomain& domain, Lattice lattice,
                  const RelaxOptions& options);

/// Fluid volumes V_i = 1 / n_i scaled so that they sum to `domain_volume` (the exact volume when
/// the caller knows it, else N_fluid * spacing^d); walls keep spacing^d. Masses are
/// rest_density * volume for every particle, so the fluid's total mass is rest_density times the
/// domain volume. Returns the scale factor applied to 1 / n_i.
double assign_volumes(ParticleSet& particles, const FluidDomain& domain, double support,
                      double domain_volume, double rest_density = 1.0, int threads = 0);

}  // namespace sadr::geometry
