// SPDX-License-Identifier: MIT
// Inflow buffers of ssa_service (sadr/ssa/inflow.hpp): the copy number is
// re-imposed as round(c V_i) on exactly the particles inside the box at the
// time, counts elsewhere are untouched, nothing is rebuilt when nothing
// changes, and bad input is refused naming the field.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "sadr/common/status.hpp"
#include "sadr/ssa/inflow.hpp"
#include "sadr/ssa/nsm_solver.hpp"
#include "sadr/ssa/ssa_service.hpp"

namespace sadr::ssa {
namespace {

/// 10 particles on [0, 1) (periodic), dx = 0.1, m = 0.1, rho = 1 -> V = 0.1.
ParticleState chain(double shift) {
  ParticleState p;
  p.dimension = 1;
  p.resize(10, false);
  for (std::size_t i = 0; i < 10; ++i) {
    p.positions[3 * i] = std::fmod(0.05 + 0.1 * static_cast<double>(i) + shift, 1.0);
    p.masses[i] = 0.1;
    p.densities[i] = 1.0;
  }
  return p;
}

Model chain_model() {
  Model m;
  m.species = {{"A", 0.01}, {"B", 0.0}};
  m.box.dimension = 1;
  m.box.lo = {0, 0, 0};
  m.box.hi = {1, 1, 1};
  m.box.periodic = {true, false, false};
  m.smoothing_length = 0.25;
  return m;
}

TEST(Inflow, ResetsExactlyTheParticlesInsideTheBoxAsTheyMove) {
  NsmSolver solver(chain_model(), 7);
  solver.update_graph(chain(0.0));
  solver.set_counts(0, std::vector<std::int64_t>(10, 3));
  InflowBuffer b;
  b.species = 0;
  b.box.lower = {0.0, -1e300, -1e300};
  b.box.upper = {0.22, 1e300, 1e300};
  b.box.concentration = 204.0;  // round(204 * 0.1) = 20 molecules
  const std::vector<InflowBuffer> inflows{b};
  EXPECT_TRUE(apply_inflows(solver, inflows));
  std::vector<std::int64_t> want{20, 20, 3, 3, 3, 3, 3, 3, 3, 3};
  EXPECT_EQ(std::vector<std::int64_t>(solver.counts(0).begin(), solver.counts(0).end()), want);
  EXPECT_FALSE(apply_inflows(solver, inflows));  // already held: no rebuild
  // The particles move by 0.12: now particles 9 (x = 0.07) and 0 (0.17) are inside;
  // particle 1 (x = 0.27) has left and keeps what it had.
  solver.update_graph(chain(0.12));
  EXPECT_TRUE(apply_inflows(solver, inflows));
  want = {20, 20, 3, 3, 3, 3, 3, 3, 3, 20};
  EXPECT_EQ(std::vector<std::int64_t>(solver.counts(0).begin(), solver.counts(0).end()), want);
  EXPECT_EQ(solver.counts(1)[0], 0);  // other species untouched
}

TEST(Inflow, BadInputNamesTheField) {
  v1::SsaModel m;
  auto* in = m.add_inflows();
  in->set_species("C");
  in->add_lower(0.0);
  in->add_upper(1.0);
  in->set_concentration(1.0);
  const std::vector<std::string> names{"A", "B"};
  auto message = [&] {
    try {
      (void)inflows_from_proto(m, 1, names);
    } catch (const InvalidArgument& e) {
      return std::string(e.what());
    }
    return std::string("<no error>");
  };
  EXPECT_NE(message().find("init.model.inflows[0].species = 'C' is not a stochastic species"),
            std::string::npos)
      << message();
  in->set_species("A");
  in->set_concentration(-2.0);
  EXPECT_NE(message().find("init.model.inflows[0].concentration = -2 (allowed: finite, >= 0"),
            std::string::npos)
      << message();
  in->set_concentration(1.0);
  in->set_lower(0, 2.0);
  EXPECT_NE(message().find("axis 0 has lower = 2 > upper = 1"), std::string::npos) << message();
  in->set_lower(0, 0.0);
  in->add_lower(0.0);
  EXPECT_NE(message().find("lower/upper have 2/1 entries (allowed: 1, one per axis)"),
            std::string::npos)
      << message();
}

}  // namespace
}  // namespace sadr::ssa
