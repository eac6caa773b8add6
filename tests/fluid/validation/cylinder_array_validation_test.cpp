// SPDX-License-Identifier: MIT
// Validation: the drag of Stokes flow through a square periodic array of cylinders (2D, SDPD,
// k_B T = 0) from the force on the body (FluidModel::body_forces) against Sangani & Acrivos
// (1982): F / (mu U) = 4 pi / (-ln(c)/2 - 0.738 + c - 0.887 c^2 + 2.039 c^3), c the solid area
// fraction, U the superficial velocity (the mean over the whole cell), F the drag per unit length
// in the pressure-driven array: the mean pressure gradient times the cell area A. Driven by the
// body acceleration g on the fluid alone, the same flow puts rho g (1 - c) A on the cylinder, so F
// = (force on the body) / (1 - c) (the cylinder's share of the pressure gradient is missing). A
// unit cell with a disk of c = 0.1 at 20, 40 and 80 particles across, driven by the body
// acceleration g, run to steady state (t = 0.6, about 13 relaxation times K/nu); F and U are the
// means over the last 0.2. c is the particles' own: 1 - (fluid particles' volume) / (cell area).
// Prints RESULT lines (docs/fluid-core.md section 5, bench/results/body_forces.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <numbers>

#include "../disk_in_box_scene.hpp"
#include "sdpd/sdpd_backend.hpp"

namespace sadr::fluid::test {
namespace {

// c0 = 20, Mach ~ 0.002: at c0 = 10 the drag at 40 across is 2 % lower (compressibility)
constexpr double kC = 0.1, kEta = 1.0, kG = 1.0, kC0 = 20.0;

double sangani_acrivos(double c) {
  return 4.0 * std::numbers::pi /
         (-0.5 * std::log(c) - 0.738 + c - 0.887 * c * c + 2.039 * c * c * c);
}

struct Drag {
  double c = 0, drag = 0, reference = 0, error = 0, balance = 0, reynolds = 0;
};

Drag run_array(int n, WallModel wm) {
  const double radius = std::sqrt(kC / std::numbers::pi);
  DiskInBox s = disk_in_box(2, n, wm, radius, kEta, kG, kC0);
  SdpdBackend b;
  b.initialize(s.model, s.state, {});
  constexpr double kTau = 0.02, kEnd = 0.6, kAverageFrom = 0.4;
  const int steps = static_cast<int>(std::lround(kEnd / kTau));
  double f_sum = 0, u_sum = 0, fluid_volume = 0, mass = 0;
  int samples = 0;
  for (int k = 0; k < steps; ++k) {
    const StepReport rep = b.advance(static_cast<std::uint64_t>(k), kTau);
    if (rep.time < kAverageFrom + 1e-9) continue;
    ParticleState st;
    b.read_state(st);
    double px = 0;
    fluid_volume = 0;
    mass = 0;
    for (std::size_t i = 0; i < st.size(); ++i) {
      if (st.kind(i) != ParticleKind::kFluid) continue;
      px += st.masses[i] * st.velocities[3 * i];
      fluid_volume += s.state.masses[i] / s.state.densities[i];  // initial V_i = dx^2
      mass += st.masses[i];
    }
    f_sum += rep.body_forces.at(0).force[0];
    u_sum += px / s.model.reference_density;  // the flux through the unit cell
    ++samples;
  }
  Drag d;
  const double f = f_sum / samples, u = u_sum / samples;
  d.c = 1.0 - fluid_volume;
  d.drag = f / ((1.0 - d.c) * kEta * u);  // rho g A: see the top of the file
  d.reference = sangani_acrivos(d.c);
  d.error = d.drag / d.reference - 1.0;
  d.balance = f / (mass * kG) - 1.0;
  d.reynolds = s.model.reference_density * u * 2.0 * radius / kEta;
  return d;
}

// Every resolution within `tolerance` of the reference, and the error shrinking with resolution.
void check(const char* walls, WallModel wm, std::initializer_list<int> resolutions,
           double tolerance) {
  double previous = 1e300;
  for (const int n : resolutions) {
    const Drag d = run_array(n, wm);
    std::printf(
        "RESULT cylinder_array walls=%s n=%d c=%.4f F/(mu U)=%.3f sangani_acrivos=%.3f "
        "error=%+.4f F/(M g)-1=%+.2e Re=%.3g\n",
        walls, n, d.c, d.drag, d.reference, d.error, d.balance, d.reynolds);
    std::fflush(stdout);
    EXPECT_LT(std::fabs(d.error), tolerance) << walls << " n = " << n;
    EXPECT_LT(std::fabs(d.error), previous) << walls << " n = " << n << ": no convergence";
    EXPECT_LT(std::fabs(d.balance), 2e-3) << walls << " n = " << n;  // steady
    previous = std::fabs(d.error);
  }
}

// Measured: -0.078, -0.045, -0.023 (bench/results/body_forces.md).
TEST(CylinderArrayValidation, AdamiWallsApproachSanganiAcrivos) {
  check("adami", WallModel::kAdami, {20, 40, 80}, 0.10);
}

// Measured: -0.239, -0.143, -0.077.
TEST(CylinderArrayValidation, StationaryWallsApproachSanganiAcrivos) {
  check("stationary", WallModel::kStationary, {20, 40, 80}, 0.31);
}

}  // namespace
}  // namespace sadr::fluid::test
