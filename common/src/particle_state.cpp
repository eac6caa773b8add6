// SPDX-License-Identifier: MIT
#include "sadr/common/particle_state.hpp"

#include <cmath>
#include <string>

#include "sadr/common/status.hpp"

namespace sadr {

std::string_view to_string(ParticleKind kind) {
  switch (kind) {
    case ParticleKind::kFluid:
      return "fluid";
    case ParticleKind::kWall:
      return "wall";
    case ParticleKind::kInlet:
      return "inlet";
    case ParticleKind::kOutlet:
      return "outlet";
  }
  return "unknown";
}

void Box::validate() const {
  if (dimension < 1 || dimension > 3) {
    throw InvalidArgument("box.dimension = " + std::to_string(dimension) + " (allowed: 1, 2, 3)");
  }
  for (int a = 0; a < dimension; ++a) {
    if (!(std::isfinite(lo[a]) && std::isfinite(hi[a]) && hi[a] > lo[a])) {
      throw InvalidArgument("box axis " + std::to_string(a) + ": hi (" + format_value(hi[a]) +
                            ") must be finite and greater than lo (" + format_value(lo[a]) + ")");
    }
    // Both ends finite, the length not (-1e308 to 1e308): positions became NaN in the
    // fluid's cell binning (found by fuzz_fluid_requests).
    if (!std::isfinite(hi[a] - lo[a])) {
      throw InvalidArgument("box axis " + std::to_string(a) +
                            ": length hi - lo = " + format_value(hi[a]) + " - " +
                            format_value(lo[a]) + " overflows (must be finite)");
    }
  }
}

void ParticleState::resize(std::size_t n, bool with_velocities) {
  positions.assign(3 * n, 0.0);
  velocities.assign(with_velocities ? 3 * n : 0, 0.0);
  densities.assign(n, 1.0);
  masses.assign(n, 1.0);
  kinds.assign(n, ParticleKind::kFluid);
  ids.resize(n);
  for (std::size_t i = 0; i < n; ++i) ids[i] = i;
}

namespace {
void check_len(const char* field, std::size_t got, std::size_t want, bool optional) {
  if (got == want || (optional && got == 0)) return;
  throw InvalidArgument(std::string("particle state: field '") + field + "' has " +
                        std::to_string(got) + " entries, expected " + std::to_string(want) +
                        (optional ? " (or 0)" : ""));
}
}  // namespace

// Also checks that each volume m_i / rho_i is a finite normal number (below).
void ParticleState::validate() const {
  const std::size_t n = size();
  if (dimension < 1 || dimension > 3) {
    throw InvalidArgument("particle state: dimension = " + std::to_string(dimension) +
                          " (allowed: 1, 2, 3)");
  }
  check_len("positions", positions.size(), 3 * n, false);
  check_len("velocities", velocities.size(), 3 * n, true);
  check_len("masses", masses.size(), n, false);
  check_len("kinds", kinds.size(), n, true);
  check_len("ids", ids.size(), n, true);
  for (std::size_t i = 0; i < n; ++i) {
    if (!(std::isfinite(masses[i]) && masses[i] > 0)) {
      throw InvalidArgument("particle " + std::to_string(i) +
                            ": mass = " + format_value(masses[i]) + " (must be finite and > 0)");
    }
    if (!(std::isfinite(densities[i]) && densities[i] > 0)) {
      throw InvalidArgument("particle " + std::to_string(i) + ": density = " +
                            format_value(densities[i]) + " (must be finite and > 0)");
    }
    // Both may be fine while V = m / rho is not (1 / 1e-310 overflows; 1e-310 / 1 is
    // subnormal): the SSA's rates divide and multiply by V (found by fuzz_ssa_requests).
    const double volume = masses[i] / densities[i];
    if (!std::isnormal(volume)) {
      throw InvalidArgument("particle " + std::to_string(i) + ": volume mass / density = " +
                            format_value(masses[i]) + " / " + format_value(densities[i]) + " = " +
                            format_value(volume) + " (must be a finite, normal number > 0)");
    }
    for (std::size_t a = 0; a < 3 && !velocities.empty(); ++a) {
      // (a NaN velocity made every position NaN after one step: fuzz_fluid_requests)
      if (!std::isfinite(velocities[3 * i + a])) {
        throw InvalidArgument("particle " + std::to_string(i) + ": velocity[" + std::to_string(a) +
                              "] = " + format_value(velocities[3 * i + a]) + " (must be finite)");
      }
    }
    for (int a = 0; a < 3; ++a) {
      if (!std::isfinite(positions[3 * i + a])) {
        throw InvalidArgument("particle " + std::to_string(i) + ": position[" + std::to_string(a) +
                              "] = " + format_value(positions[3 * i + a]) + " (must be finite)");
      }
    }
  }
}

}  // namespace sadr
