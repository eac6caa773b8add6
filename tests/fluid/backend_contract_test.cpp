// SPDX-License-Identifier: MIT
/// \file backend_contract_test.cpp
/// The backend contract: property tests written once and run on every backend the registry
/// holds (register_builtin_backends, generated from SADR_FLUID_BACKENDS), so a new backend runs
/// them without anyone adding it. What a backend does is read from its schema entry
/// (capabilities); the scene is backend_contract_scene.hpp.
/// Asserted: (1) total momentum is conserved to rounding with noise on (pairwise-antisymmetric
/// noise), for backends that move particles and have thermal noise; (2) same seed -> bit-identical
/// state, different seed -> different state (when the backend has thermal noise); (3) save/restore
/// continues bit-identically; (4) 1 thread and 2 threads give bit-identical states (OpenMP builds);
/// (5) current_substep_bound() at t = 0 (the figure the fluid service reports to the plan)
/// predicts the first advance's sub-steps and leaves the trajectory as it is.
#include <gtest/gtest.h>

#include "backend_contract_scene.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sadr/common/rng.hpp"
#include "sadr/fluid/builtin_backends.hpp"
#include "sadr/fluid/fluid_backend.hpp"
#ifdef _OPENMP
#include <omp.h>
#endif

namespace sadr::fluid::generic_test {
namespace {

std::unique_ptr<FluidBackend> run(const BackendCase& bc, std::uint64_t seed, int steps) {
  auto b = bc.make();
  const Scene s = make_scene(bc, seed);
  b->initialize(s.model, s.state, s.conc);
  for (int k = 0; k < steps; ++k) b->advance(static_cast<std::uint64_t>(k), bc.time_step);
  return b;
}

void expect_identical(const FluidBackend& a, const FluidBackend& b) {
  ParticleState sa, sb;
  a.read_state(sa);
  b.read_state(sb);
  ASSERT_EQ(sa.positions.size(), sb.positions.size());
  for (std::size_t k = 0; k < sa.positions.size(); ++k) {
    ASSERT_EQ(sa.positions[k], sb.positions[k]) << "position entry " << k;
  }
  for (std::size_t k = 0; k < sa.velocities.size(); ++k) {
    ASSERT_EQ(sa.velocities[k], sb.velocities[k]) << "velocity entry " << k;
  }
  const auto& ca = a.concentrations(0);
  const auto& cb = b.concentrations(0);
  for (std::size_t k = 0; k < ca.size(); ++k) ASSERT_EQ(ca[k], cb[k]) << "concentration " << k;
  EXPECT_EQ(a.time(), b.time());
}

class BackendContract : public ::testing::TestWithParam<BackendCase> {};

TEST_P(BackendContract, SubstepBoundPredictsTheFirstAdvance) {
  const auto& bc = GetParam();
  const Scene s = make_scene(bc, 7);
  auto asked = bc.make();
  asked->initialize(s.model, s.state, s.conc);
  const SubstepBound bound = asked->current_substep_bound();
  ASSERT_GT(bound.dt, 0.0);
  EXPECT_LE(bound.dt, bound.limit) << "no max_time_step: the limit itself";
  const StepReport rep = asked->advance(0, bc.time_step);
  const double predicted = std::isfinite(bound.dt)
                               ? std::max(1.0, std::ceil(bc.time_step / bound.dt * (1.0 - 1e-12)))
                               : 1.0;
  // exact for the uniform rule (tdpd); the adaptive one re-reads the limits every sub-step
  EXPECT_NEAR(static_cast<double>(rep.substeps), predicted, 1.0)
      << bc.name << ": bound " << bound.dt << " (" << bound.criterion << ")";
  auto plain = run(bc, 7, 1);  // never asked
  expect_identical(*asked, *plain);
}

TEST_P(BackendContract, MomentumConservedWithNoise) {
  const auto& bc = GetParam();
  auto b = run(bc, 7, bc.steps);
  const auto& caps = b->capabilities();
  if (!caps.moves_particles || !caps.thermal_noise) {
    GTEST_SKIP() << bc.name << " has no thermal noise that moves particles";
  }
  ParticleState s;
  b->read_state(s);
  double p[3] = {0, 0, 0}, scale = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    for (int a = 0; a < 3; ++a) {
      p[a] += s.masses[i] * s.velocities[3 * i + a];
      scale += s.masses[i] * std::abs(s.velocities[3 * i + a]);
    }
  }
  ASSERT_GT(scale, 0.0) << "noise must have set the particles in motion";
  for (int a = 0; a < 3; ++a) EXPECT_LT(std::abs(p[a]), 1e-12 * scale) << "axis " << a;
}

TEST_P(BackendContract, SameSeedSameResultOtherSeedDiffers) {
  const auto& bc = GetParam();
  auto a = run(bc, 11, bc.steps);
  auto b = run(bc, 11, bc.steps);
  expect_identical(*a, *b);
  if (!a->capabilities().thermal_noise) return;
  auto c = run(bc, 12, bc.steps);
  ParticleState sa, sc;
  a->read_state(sa);
  c->read_state(sc);
  EXPECT_NE(sa.positions, sc.positions) << "the seed must change the noise";
}

TEST_P(BackendContract, SaveRestoreContinuesIdentically) {
  const auto& bc = GetParam();
  auto a = run(bc, 5, bc.steps);
  const std::string blob = a->save();
  auto b = bc.make();
  const Scene s = make_scene(bc, 5);
  b->initialize(s.model, s.state, s.conc);
  b->restore(blob);
  for (int k = bc.steps; k < 2 * bc.steps; ++k) {
    a->advance(static_cast<std::uint64_t>(k), bc.time_step);
    b->advance(static_cast<std::uint64_t>(k), bc.time_step);
  }
  expect_identical(*a, *b);
  EXPECT_EQ(a->save(), b->save());
}

TEST_P(BackendContract, ThreadCountIndependent) {
#ifdef _OPENMP
  const auto& bc = GetParam();
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  auto a = run(bc, 3, bc.steps);
  omp_set_num_threads(2);
  auto b = run(bc, 3, bc.steps);
  omp_set_num_threads(saved);
  expect_identical(*a, *b);
#else
  GTEST_SKIP() << "built without OpenMP";
#endif
}

/// Every registered backend, with the scene's knobs from its schema entry: thermal noise on
/// (k_B T = 1e-3, small against the sound speed's kinetic scale) where the backend has it.
std::vector<BackendCase> registered_backends() {
  BackendRegistry reg;
  register_builtin_backends(reg);
  std::vector<BackendCase> cases;
  for (const std::string& name : reg.names()) {
    BackendCase c;
    c.name = name;
    c.make = [name] {
      BackendRegistry r;
      register_builtin_backends(r);
      return r.create(name);
    };
    c.temperature = reg.create(name)->capabilities().thermal_noise ? 1e-3 : 0.0;
    cases.push_back(c);
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Registered, BackendContract, ::testing::ValuesIn(registered_backends()),
                         case_name);

}  // namespace
}  // namespace sadr::fluid::generic_test
