// SPDX-License-Identifier: MIT
/// Property tests of the tDPD fluid: the thermostat reaches k_B T (fluctuation-dissipation
/// of the pair noise) and total species amount is conserved in a periodic box.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "backend_contract_scene.hpp"
#include "tdpd/tdpd_backend.hpp"

namespace sadr::fluid {
namespace {

TEST(TdpdProperty, ThermostatReachesTemperatureAndConservesSpecies) {
  generic_test::BackendCase bc;
  bc.name = "tdpd";
  const auto scene = generic_test::make_scene(bc, 21);
  TdpdBackend b;
  b.initialize(scene.model, scene.state, scene.conc);
  const double total0 = std::accumulate(scene.conc[0].begin(), scene.conc[0].end(), 0.0);
  double kin = 0;
  int samples = 0;
  for (std::uint64_t k = 0; k < 300; ++k) {
    b.advance(k, 0.01);
    if (k >= 100 && k % 10 == 0) {
      ParticleState s;
      b.read_state(s);
      double e = 0;
      for (double v : s.velocities) e += v * v;
      kin += e / static_cast<double>(3 * s.size());  // k_B T estimate, unit mass
      ++samples;
    }
  }
  const double kbt = kin / samples;
  // Groot-Warren lambda = 0.5 at dt = 0.01 gives k_B T within ~1%; statistical error ~1%.
  EXPECT_NEAR(kbt, 1.0, 0.04) << "measured k_B T";
  const auto& c = b.concentrations(0);
  const double total = std::accumulate(c.begin(), c.end(), 0.0);
  EXPECT_NEAR(total, total0, 1e-10 * total0);
  for (double ci : c) {
    EXPECT_GE(ci, -1e-12);
    EXPECT_LE(ci, 1.0 + 1e-12);  // the Fickian flux is a monotone average for dt below eq 13
  }
}

}  // namespace
}  // namespace sadr::fluid
