// SPDX-License-Identifier: MIT
// Validation (statistical): SDPD equipartition in a periodic box at rest. The kinetic
// temperature T_kin = sum_i m_i |v_i - v_cm|^2 / (d (N - 1)) averaged over time must equal
// k_B T within tau + z* SE, where tau = 3% is the modelling tolerance for the finite-dt bias
// of the trapezoidal scheme (dt ~ 0.1 of the velocity relaxation time), z* = 3.89
// (alpha_fw = 1e-4, M = 1 per dimension) and SE is the batch-means standard error
// (10 batches, each much longer than the velocity decorrelation time). False-failure rate
// <= 1e-4 per dimension if the scheme is unbiased to within tau.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "../fluid_test_scenes.hpp"
#include "line_scenes.hpp"
#include "sdpd/sdpd_backend.hpp"

namespace sadr::fluid::test {
namespace {

// The check, with or without the transport velocity (fluid parameter transport_velocity).
void check_equipartition(int dim, bool tvf) {
  LatticeSpec ls;
  ls.dimension = dim;
  ls.n = dim == 3 ? std::array<int, 3>{8, 8, 8} : std::array<int, 3>{20, 20, 1};
  if (dim == 1) ls.n = {200, 1, 1};
  ls.dx = 1.0;
  FluidModel m;
  const ParticleState p = make_lattice(ls, m.box);
  m.smoothing_length = dim == 3 ? 2.5 : 3.0;
  m.sound_speed = 10.0;
  m.shear_viscosity = 1.0;
  const double kT = 0.01;
  m.temperature = kT;
  m.seed = 2024;
  m.max_time_step = 0.02;
  // Summation density: the GENERIC-compliant SDPD (drawert2019 sec. 2.1.1). The continuity
  // equation's Molteni-Colagrossi density diffusion is a dissipation without a matching noise
  // and cools the fluid (measured T_kin/kT = 0.69 / 0.90 / 0.95 in 1D / 2D / 3D with it).
  m.density_mode = DensityMode::kSummation;
  if (tvf) {  // p_b = 0.2 rho_0 c_0^2 (see the TVF test below)
    m.backend_parameters["transport_velocity"] = 1.0;
    m.backend_parameters["shift_pressure"] = 0.2;
  }
  SdpdBackend b;
  b.initialize(m, p, {});
  const int equil = 1000, batches = 10, per_batch = 300, every = 5;
  for (int s = 0; s < equil; ++s) b.advance(static_cast<std::uint64_t>(s), 0.02);
  std::vector<double> batch_mean;
  std::uint64_t step = equil;
  ParticleState st;
  for (int bt = 0; bt < batches; ++bt) {
    double sum = 0;
    int cnt = 0;
    for (int s = 0; s < per_batch; ++s) {
      b.advance(step++, 0.02);
      if (s % every) continue;
      b.read_state(st);
      double vcm[3] = {0, 0, 0}, mt = 0, ke = 0;
      for (std::size_t i = 0; i < st.size(); ++i) {
        mt += st.masses[i];
        for (int a = 0; a < 3; ++a) vcm[a] += st.masses[i] * st.velocities[3 * i + a];
      }
      for (std::size_t i = 0; i < st.size(); ++i) {
        for (int a = 0; a < dim; ++a)
          ke += st.masses[i] * std::pow(st.velocities[3 * i + a] - vcm[a] / mt, 2);
      }
      sum += ke / (dim * (static_cast<double>(st.size()) - 1));
      ++cnt;
    }
    batch_mean.push_back(sum / cnt);
  }
  double mean = 0, var = 0;
  for (double x : batch_mean) mean += x / batches;
  for (double x : batch_mean) var += (x - mean) * (x - mean) / (batches - 1);
  const double se = std::sqrt(var / batches);
  char line[200];
  std::snprintf(line, sizeof line, "case=equipartition%s dim=%d T_kin/kT=%.4f SE/kT=%.4f",
                tvf ? "_tvf" : "", dim, mean / kT, se / kT);
  report(line);
  EXPECT_LE(std::fabs(mean - kT), 0.03 * kT + 3.89 * se) << line;  // statistical (see file comment)
}

class Equipartition : public ::testing::TestWithParam<int> {};

TEST_P(Equipartition, KineticTemperatureMatchesKT) {
  check_equipartition(GetParam(), false);
}

INSTANTIATE_TEST_SUITE_P(Dims, Equipartition, ::testing::Values(1, 2, 3));

// The transport velocity moves the particles with v + s, s deterministic (the shift
// pressure), and adds the deterministic A-tensor term to the momentum; the noise stays on the
// momentum equation with its amplitude unchanged. The shift is a drift of the positions
// without a matching noise: it relaxes the density fluctuations and cools the fluid, by an
// amount that grows with p_b (measured 2D, this set-up: T_kin/kT = 0.921 +- 0.005 at the
// default p_b = 5 rho_0 c_0^2, 0.915 with dt halved, 0.921 without the A term; 0.944 at
// p_b = 1; 0.987 +- 0.004 at p_b = 0.2). The check runs at p_b = 0.2, where the bound of the
// plain backend holds. Same bound and false-failure rate as above.
TEST(EquipartitionTransportVelocity, KineticTemperatureMatchesKT2D) {
  check_equipartition(2, true);
}

}  // namespace
}  // namespace sadr::fluid::test
