// SPDX-License-Identifier: MIT
/// Unit tests of the tDPD backend: pair force and flux against li2015 eqs 3-6 by hand,
/// conservation of species, stability refusal/forcing, blow-up diagnosis, SSA-facing state,
/// restart blob checks and registry wiring.
#include <gtest/gtest.h>

#include <map>

#include <cmath>
#include <numeric>

#include "sadr/common/status.hpp"
#include "sadr/fluid/builtin_backends.hpp"
#include "tdpd/tdpd_backend.hpp"

namespace sadr::fluid {
namespace {

/// Two (or more) particles in a periodic 3D box of side 8 with r_c = 1.58.
struct Pair {
  FluidModel model;
  ParticleState state;
  std::vector<std::vector<double>> conc;
  Pair(double r, double kbt) {
    model.box.dimension = 3;
    model.box.hi = {8, 8, 8};
    model.box.periodic = {true, true, true};
    model.smoothing_length = 1.58;
    model.reference_density = 4.0;
    model.temperature = kbt;
    SpeciesSpec a;
    a.def.name = "A";
    a.def.diffusivity = 0.3;  // kappa
    model.species.push_back(a);
    state.dimension = 3;
    state.resize(2, true);
    state.positions = {4.0, 4.0, 4.0, 4.0 + r * 0.6, 4.0 + r * 0.8, 4.0};
    state.velocities = {0.2, -0.1, 0.05, -0.3, 0.4, 0.0};
    state.densities = {4.0, 4.0};
    state.masses = {1.0, 1.0};
    conc = {{2.0, 0.5}};
  }
};

TEST(TdpdUnit, PairForceAndFluxMatchTheFormulas) {
  const double r = 0.9;
  Pair p(r, 0.0);
  TdpdBackend b;
  b.initialize(p.model, p.state, p.conc);
  std::vector<double> f;
  std::vector<std::vector<double>> q;
  b.evaluate_current(0, 0.01, f, q);
  const double e[3] = {-0.6, -0.8, 0.0};  // e_ij = (x_0 - x_1)/r for i = 0
  const double v01[3] = {0.5, -0.5, 0.05};
  const double ev = e[0] * v01[0] + e[1] * v01[1] + e[2] * v01[2];
  const double rc = 1.58;
  const double wc = 1.0 - r / rc;
  const double wd = std::pow(wc, 0.41);
  const double fmag = 18.75 * wc - 4.5 * wd * ev;
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(f[a], fmag * e[a], 1e-12) << a;
    EXPECT_EQ(f[a], -f[3 + a]) << "pair force must be exactly antisymmetric";
  }
  const double qexp = 0.3 * wc * wc * (0.5 - 2.0);
  EXPECT_NEAR(q[0][0], qexp, 1e-14);
  EXPECT_EQ(q[0][0], -q[0][1]);
}

TEST(TdpdUnit, NoInteractionBeyondTheCutoffs) {
  Pair p(1.6, 0.0);
  TdpdParameters prm;
  prm.r_cc = 1.0;
  TdpdBackend b;
  b.set_parameters(prm);
  b.initialize(p.model, p.state, p.conc);
  std::vector<double> f;
  std::vector<std::vector<double>> q;
  b.evaluate_current(0, 0.01, f, q);
  for (double fk : f) EXPECT_EQ(fk, 0.0);
  EXPECT_EQ(q[0][0], 0.0);
  Pair p2(1.2, 0.0);  // inside r_c, outside r_cc = 1
  b.initialize(p2.model, p2.state, p2.conc);
  b.evaluate_current(0, 0.01, f, q);
  EXPECT_NE(f[0], 0.0);
  EXPECT_EQ(q[0][0], 0.0);
}

TEST(TdpdUnit, ZeroTemperatureIsDeterministicAndSeedIndependent) {
  Pair p(0.9, 0.0);
  TdpdBackend a, b;
  a.initialize(p.model, p.state, p.conc);
  p.model.seed = 99;
  b.initialize(p.model, p.state, p.conc);
  for (std::uint64_t k = 0; k < 10; ++k) {
    a.advance(k, 0.01);
    b.advance(k, 0.01);
  }
  EXPECT_EQ(a.save(), b.save()) << "k_B T = 0 must not draw random numbers";
}

TEST(TdpdUnit, SpeciesAndMomentumConservedOverSteps) {
  Pair p(0.9, 1.0);
  TdpdBackend b;
  b.initialize(p.model, p.state, p.conc);
  for (std::uint64_t k = 0; k < 50; ++k) b.advance(k, 0.01);
  const auto& c = b.concentrations(0);
  EXPECT_NEAR(c[0] + c[1], 2.5, 1e-13);
  EXPECT_LT(std::abs(c[0] - c[1]), 1.5) << "the flux must have relaxed the difference";
  ParticleState s;
  b.read_state(s);
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(s.velocities[a] + s.velocities[3 + a],
                p.state.velocities[a] + p.state.velocities[3 + a], 1e-13);
  }
}

TEST(TdpdUnit, ReadStateReportsUnitMassesAndKernelDensity) {
  // Simple cubic lattice at number density 4 (spacing 4^(-1/3)): kernel-summed density ~ 4.
  FluidModel m;
  m.box.dimension = 3;
  const int na = 10;
  const double dx = std::cbrt(0.25);
  m.box.hi = {na * dx, na * dx, na * dx};
  m.box.periodic = {true, true, true};
  m.smoothing_length = 1.58;
  m.reference_density = 4.0;
  ParticleState s;
  s.dimension = 3;
  s.resize(na * na * na, true);
  for (int i = 0; i < na * na * na; ++i) {
    s.positions[3 * i] = (i % na + 0.5) * dx;
    s.positions[3 * i + 1] = ((i / na) % na + 0.5) * dx;
    s.positions[3 * i + 2] = (i / (na * na) + 0.5) * dx;
    s.densities[i] = 4.0;
    s.masses[i] = 1.0;
  }
  TdpdBackend b;
  b.initialize(m, s, {});
  ParticleState out;
  b.read_state(out);
  ASSERT_EQ(out.size(), s.size());
  for (std::size_t i = 0; i < out.size(); ++i) {
    EXPECT_EQ(out.masses[i], 1.0);
    EXPECT_NEAR(out.densities[i], 4.0, 0.2) << i;
  }
  EXPECT_NO_THROW(out.validate());
}

// max_time_step above the diffusion limit is an upper bound that does not bind (the old rule
// refused it): the sub-steps are the automatic ones; force_time_step takes it as the sub-step.
TEST(TdpdUnit, MaxTimeStepAboveTheDiffusionLimitIsAnUpperBoundUnlessForced) {
  Pair p(0.9, 0.0);
  p.model.species[0].def.diffusivity = 50.0;  // li2015 eq 13 limit ~ 1/(4 * 50 * 1.65) = 3e-3
  p.model.max_time_step = 0.0;                // automatic: sub-steps below the limit
  TdpdBackend b;
  b.initialize(p.model, p.state, p.conc);
  const auto lim = b.current_limits();
  EXPECT_NEAR(lim.diffusion, 15.0 / (2.0 * M_PI * 4.0 * 50.0 * std::pow(1.58, 3)), 1e-12);
  const auto automatic = b.advance(0, 0.01);
  EXPECT_GE(automatic.substeps, 4u);
  EXPECT_EQ(automatic.limiting_criterion, "diffusion");
  p.model.max_time_step = 0.01;
  TdpdBackend capped;
  capped.initialize(p.model, p.state, p.conc);
  EXPECT_EQ(capped.advance(0, 0.01).substeps, automatic.substeps);
  EXPECT_EQ(capped.concentrations(0), b.concentrations(0));
  p.model.force_time_step = true;
  b.initialize(p.model, p.state, p.conc);
  EXPECT_EQ(b.advance(0, 0.01).substeps, 1u);
}

TEST(TdpdUnit, BlowUpNamesStepParticleQuantityAndValue) {
  Pair p(1.7, 0.0);  // beyond r_c: particle 1 flies alone
  p.model.box.periodic = {false, true, true};
  p.state.velocities = {0, 0, 0, 1e6, 0, 0};
  p.model.max_time_step = 0.01;
  p.model.force_time_step = true;
  TdpdBackend b;
  b.initialize(p.model, p.state, p.conc);
  try {
    b.advance(3, 0.01);
    FAIL() << "expected NumericalFailure";
  } catch (const NumericalFailure& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("step 3"), std::string::npos) << m;
    EXPECT_NE(m.find("particle id 1 "), std::string::npos) << m;
    EXPECT_NE(m.find("position[0] = "), std::string::npos) << m;
    // The fluid core's report (backend_base.hpp): every field, the value and the limit broken.
    std::map<std::string, std::string> d(e.details().begin(), e.details().end());
    EXPECT_EQ(d["step"], "3");
    EXPECT_EQ(d["substep"], "0");
    EXPECT_EQ(d["particle_id"], "1");
    EXPECT_EQ(d["field"], "position[0]");
    EXPECT_GT(std::stod(d["value"]), p.model.box.hi[0]) << d["value"];
    EXPECT_NE(d["limit"].find("left the box"), std::string::npos) << d["limit"];
  }
}

TEST(TdpdUnit, RejectsBadParametersAndForeignBlobs) {
  Pair p(0.9, 0.0);
  TdpdParameters prm;
  prm.r_cc = 2.0;  // > r_c
  TdpdBackend b;
  b.set_parameters(prm);
  EXPECT_THROW(b.initialize(p.model, p.state, p.conc), InvalidArgument);
  b.set_parameters(TdpdParameters{});
  b.initialize(p.model, p.state, p.conc);
  EXPECT_THROW(b.restore("not a blob"), InvalidArgument);
  const std::string blob = b.save();
  EXPECT_THROW(b.restore(blob.substr(0, blob.size() - 3)), InvalidArgument);
  EXPECT_NO_THROW(b.restore(blob));
}

TEST(TdpdUnit, RegisteredUnderItsName) {
  BackendRegistry reg;
  register_builtin_backends(reg);
  if (!reg.contains("tdpd")) register_tdpd_backend(reg);  // once the lead lists it
  auto b = reg.create("tdpd");
  EXPECT_EQ(b->name(), "tdpd");
  EXPECT_TRUE(b->capabilities().moves_particles);
}

TEST(TdpdUnit, SetConcentrationsRefreshesTheFluxes) {
  Pair p(0.9, 0.0);
  TdpdBackend b;
  b.initialize(p.model, p.state, {{0.0, 0.0}});
  b.advance(0, 0.01);
  const std::vector<double> c = {2.0, 0.5};
  b.set_concentrations(0, c);
  b.advance(1, 0.01);
  const auto& after = b.concentrations(0);
  EXPECT_LT(after[0], 2.0) << "the stale (zero) flux was used";
  EXPECT_GT(after[1], 0.5);
  EXPECT_NEAR(after[0] + after[1], 2.5, 1e-14);
}

}  // namespace
}  // namespace sadr::fluid
