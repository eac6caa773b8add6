// SPDX-License-Identifier: MIT
// Property: state blobs written by earlier builds still restore, bit-identically.
//
// tests/fluid/data/legacy_blobs/ holds, per scene, two blobs written by the build of commit
// 263b868 (before the fluid core owned the blob header): `<case>.3.blob` after steps 0..2 and
// `<case>.6.blob` after steps 0..5. Asserted, per backend and layout (sdpd bulk = v2, sdpd
// with walls and species = v2, sdpd open boundary = v3, static = v1, tdpd = v3):
//  (1) restoring the step-3 blob and advancing steps 3..5 gives bit for bit the state of the
//      step-6 blob (positions, velocities, densities, kinds, concentrations, time);
//  (2) the same state as a run of this build from initialize() through step 5 (densities too);
//  (3) the blob this build writes after (1) restores to the same state again.
// Regenerate (only when a layout change is intended, with the build that wrote them):
//   SADR_WRITE_LEGACY_BLOBS=tests/fluid/data/legacy_blobs build/ci/bin/fluid_property_tests
//     --gtest_filter='LegacyBlobs*'
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "fluid_test_scenes.hpp"
#include "open_channel_scene.hpp"
#include "sadr/fluid/builtin_backends.hpp"

namespace sadr::fluid {
namespace {

struct LegacyScene {
  std::string backend;
  FluidModel model;
  ParticleState state;
  std::vector<std::vector<double>> conc;
  double time_step = 0.01;
};

/// A linear profile along x for species 0 (and nothing else).
std::vector<std::vector<double>> ramp(const ParticleState& p) {
  std::vector<double> c(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) c[i] = 1.0 + 0.5 * p.positions[3 * i];
  return {c};
}

LegacyScene make_case(const std::string& name) {
  LegacyScene s;
  if (name == "sdpd_bulk" || name == "sdpd_walls" || name == "static") {
    test::LatticeSpec ls;
    ls.n = {10, 8, 1};
    ls.dx = 0.1;
    ls.periodic = {true, name == "sdpd_bulk", true};
    ls.wall_layers = 3;
    s.state = test::make_lattice(ls, s.model.box);
    s.model.smoothing_length = 0.3;
    s.model.sound_speed = 10.0;
    s.model.shear_viscosity = 0.1;
    s.model.seed = 5;
    s.backend = name == "static" ? "static" : "sdpd";
    s.time_step = 0.002;
    if (name == "sdpd_bulk") {
      s.model.temperature = 1e-4;  // noise on: the half-pair path with its Philox keys
      for (std::size_t i = 0; i < s.state.size(); ++i)
        s.state.velocities[3 * i] = 0.1 * std::sin(6.283 * s.state.positions[3 * i + 1]);
    } else {
      s.model.gravity = {1.0, 0, 0};
      s.model.species.push_back({"A", 0.05, true, {}, {}});
      s.conc = ramp(s.state);
    }
    return s;
  }
  if (name == "sdpd_open") {
    test::OpenChannelSpec spec;
    spec.ny = 6;
    spec.length = 1.0;
    spec.buffer_columns = 3;
    spec.mean_velocity = 0.5;
    spec.sound_speed = 8.0;
    const test::OpenChannel c = test::make_open_channel(spec);
    s.backend = "sdpd";
    s.model = c.model;
    s.state = c.particles;
    s.time_step = 0.01;
    return s;
  }
  // tdpd: a jittered 6^3 lattice at number density 4, noise on, one transported species.
  s.backend = "tdpd";
  const int per_axis = 6;
  const double spacing = std::cbrt(0.25), len = per_axis * spacing;
  s.model.box.dimension = 3;
  s.model.box.lo = {0, 0, 0};
  s.model.box.hi = {len, len, len};
  s.model.box.periodic = {true, true, true};
  s.model.smoothing_length = 1.0;
  s.model.reference_density = 4.0;
  s.model.temperature = 1.0;
  s.model.seed = 9;
  s.model.species.push_back({"A", 2.0, true, {}, {}});
  s.state.dimension = 3;
  for (int k = 0; k < per_axis; ++k) {
    for (int j = 0; j < per_axis; ++j) {
      for (int i = 0; i < per_axis; ++i) {
        const double jit = 0.05 * spacing * std::sin(1.0 + i + 3.0 * j + 7.0 * k);
        s.state.positions.insert(s.state.positions.end(),
                                 {(i + 0.5) * spacing + jit, (j + 0.5) * spacing - jit,
                                  (k + 0.5) * spacing + 0.5 * jit});
      }
    }
  }
  const std::size_t n = s.state.positions.size() / 3;
  s.state.velocities.assign(3 * n, 0.0);
  s.state.densities.assign(n, 4.0);
  s.state.masses.assign(n, 1.0);
  s.state.kinds.assign(n, ParticleKind::kFluid);
  s.state.ids.resize(n);
  for (std::size_t i = 0; i < n; ++i) s.state.ids[i] = i;
  s.conc = ramp(s.state);
  return s;
}

std::unique_ptr<FluidBackend> start(const LegacyScene& s) {
  BackendRegistry reg;
  register_builtin_backends(reg);
  auto b = reg.create(s.backend);
  b->initialize(s.model, s.state, s.conc);
  return b;
}

void advance(FluidBackend& b, const LegacyScene& s, std::uint64_t from, std::uint64_t to) {
  for (std::uint64_t k = from; k < to; ++k) b.advance(k, s.time_step);
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Bitwise equal states. `densities`: false when one side was just restored by tdpd, which
/// recomputes its read-out densities from the positions then (the same sum in another order).
void expect_same(const FluidBackend& a, const FluidBackend& b, std::size_t species,
                 bool densities = true) {
  ParticleState sa, sb;
  a.read_state(sa);
  b.read_state(sb);
  EXPECT_EQ(a.time(), b.time());
  EXPECT_EQ(sa.positions, sb.positions);
  EXPECT_EQ(sa.velocities, sb.velocities);
  if (densities) {
    EXPECT_EQ(sa.densities, sb.densities);
  }
  EXPECT_EQ(sa.kinds, sb.kinds);
  for (std::size_t k = 0; k < species; ++k) {
    EXPECT_EQ(a.concentrations(static_cast<int>(k)), b.concentrations(static_cast<int>(k)))
        << "species " << k;
  }
}

class LegacyBlobs : public ::testing::TestWithParam<std::string> {};

TEST_P(LegacyBlobs, RestoreAndContinueBitIdentically) {
  const std::string name = GetParam();
  const LegacyScene s = make_case(name);
  if (const char* dir = std::getenv("SADR_WRITE_LEGACY_BLOBS")) {
    auto b = start(s);
    advance(*b, s, 0, 3);
    std::ofstream(std::string(dir) + "/" + name + ".3.blob", std::ios::binary) << b->save();
    advance(*b, s, 3, 6);
    std::ofstream(std::string(dir) + "/" + name + ".6.blob", std::ios::binary) << b->save();
    GTEST_SKIP() << "wrote " << dir << "/" << name << ".{3,6}.blob";
  }
  const std::string dir = std::string(SADR_SOURCE_DIR) + "/tests/fluid/data/legacy_blobs/";
  auto resumed = start(s);
  resumed->restore(read_file(dir + name + ".3.blob"));
  advance(*resumed, s, 3, 6);
  auto reference = start(s);
  reference->restore(read_file(dir + name + ".6.blob"));
  const std::size_t ns = s.model.species.size();
  const bool derived_rho = s.backend != "tdpd";
  expect_same(*resumed, *reference, ns, derived_rho);  // (1)
  auto fresh = start(s);
  advance(*fresh, s, 0, 6);
  expect_same(*fresh, *resumed, ns);  // (2)
  auto again = start(s);
  again->restore(resumed->save());
  expect_same(*again, *reference, ns);  // (3)
}

INSTANTIATE_TEST_SUITE_P(AllLayouts, LegacyBlobs,
                         ::testing::Values("sdpd_bulk", "sdpd_walls", "sdpd_open", "static",
                                           "tdpd"));

}  // namespace
}  // namespace sadr::fluid
