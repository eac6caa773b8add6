// SPDX-License-Identifier: MIT
/// \file particle_state.hpp
/// The particle arrays every part of sadr exchanges (struct of arrays).
///
/// Input specification (N particles, d = dimension):
///  - positions:  3N doubles, particle i at [3i, 3i+3) as (x, y, z); unused
///                axes (z in 2D, y and z in 1D) are 0.            [length]
///  - velocities: 3N doubles in the same layout, or empty.        [length/time]
///  - densities:  N doubles, mass density rho_i > 0.              [mass/length^d]
///  - masses:     N doubles, m_i > 0.                             [mass]
///  - kinds:      N ParticleKind values, or empty (all fluid).
///  - ids:        N stable particle ids, or empty (id = index).
/// The voxel volume of particle i is V_i = m_i / rho_i [length^d].
/// Units: one consistent system chosen by the scene (NOTATION.md).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

namespace sadr {

/// What a particle is. Wire values match sadr.common.v1.ParticleKind.
enum class ParticleKind : std::uint8_t {
  kFluid = 0,   ///< moves with the flow
  kWall = 1,    ///< stationary, no-slip, may hold Dirichlet values
  kInlet = 2,   ///< inflow buffer
  kOutlet = 3,  ///< outflow buffer
};
std::string_view to_string(ParticleKind kind);

/// Axis-aligned domain; each axis periodic or walled.
struct Box {
  int dimension = 3;                        ///< 1, 2 or 3
  std::array<double, 3> lo{0.0, 0.0, 0.0};  ///< lower corner [length]
  std::array<double, 3> hi{1.0, 1.0, 1.0};  ///< upper corner [length]
  std::array<bool, 3> periodic{false, false, false};

  [[nodiscard]] double length(int axis) const { return hi[axis] - lo[axis]; }
  /// Throws InvalidArgument if dimension is not 1-3 or an active axis has hi <= lo.
  void validate() const;
};

/// Particle arrays (see the file comment for layout and units).
struct ParticleState {
  int dimension = 3;
  std::vector<double> positions;
  std::vector<double> velocities;
  std::vector<double> densities;
  std::vector<double> masses;
  std::vector<ParticleKind> kinds;
  std::vector<std::uint64_t> ids;

  [[nodiscard]] std::size_t size() const { return densities.size(); }
  void resize(std::size_t n, bool with_velocities = true);
  [[nodiscard]] ParticleKind kind(std::size_t i) const {
    return kinds.empty() ? ParticleKind::kFluid : kinds[i];
  }
  /// Voxel volume V_i = m_i / rho_i.
  [[nodiscard]] double volume(std::size_t i) const { return masses[i] / densities[i]; }
  /// Checks array lengths, positivity of masses/densities and finiteness;
  /// throws InvalidArgument naming the field, particle index and value.
  void validate() const;
};

}  // namespace sadr
