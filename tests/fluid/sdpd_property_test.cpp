// SPDX-License-Identifier: MIT
// Property: conservation, determinism (threads, restarts, seeds) of the SDPD backend.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "fluid_test_scenes.hpp"
#include "sadr/common/rng.hpp"
#include "sadr/fluid/builtin_backends.hpp"
#include "sadr/fluid/pair_noise_batch.hpp"
#include "sadr/fluid/parallel.hpp"
#include "sdpd/sdpd_backend.hpp"
#ifdef SADR_HAVE_OPENMP
#include <omp.h>
#endif

namespace sadr::fluid {
namespace {

// A periodic box at rest, slightly jittered, with thermal noise and one species.
struct Scene {
  FluidModel model;
  ParticleState state;
  std::vector<std::vector<double>> c;
};

Scene noisy_box(int dim, double kT, int n_side = 10) {
  Scene s;
  test::LatticeSpec ls;
  ls.dimension = dim;
  ls.n = {n_side, n_side, dim == 3 ? n_side : 1};
  ls.dx = 1.0;
  ls.rho0 = 1.0;
  s.state = test::make_lattice(ls, s.model.box);
  rng::Xoshiro256 gen(3, 1);
  for (std::size_t i = 0; i < s.state.size(); ++i) {
    for (int a = 0; a < dim; ++a) s.state.positions[3 * i + a] += 0.05 * (gen.uniform() - 0.5);
    s.state.velocities[3 * i] =
        0.2 * std::sin(2.0 * M_PI * s.state.positions[3 * i + dim - 1] / n_side);
  }
  s.model.smoothing_length = dim == 3 ? 2.5 : 3.0;
  s.model.sound_speed = 10.0;
  s.model.shear_viscosity = 1.0;
  s.model.temperature = kT;
  s.model.seed = 12345;
  s.model.species.push_back({"A", 0.5, true, {}, {}});
  std::vector<double> a(s.state.size());
  for (std::size_t i = 0; i < a.size(); ++i) a[i] = std::sin(0.3 * s.state.positions[3 * i]) + 1.0;
  s.c.push_back(a);
  return s;
}

std::array<double, 3> momentum(const ParticleState& p) {
  std::array<double, 3> m{0, 0, 0};
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (int a = 0; a < 3; ++a) m[a] += p.masses[i] * p.velocities[3 * i + a];
  }
  return m;
}

class SdpdDim : public ::testing::TestWithParam<int> {};

TEST_P(SdpdDim, MomentumConservedToRoundOffWithNoise) {
  Scene s = noisy_box(GetParam(), 1.0, GetParam() == 3 ? 7 : 12);
  SdpdBackend b;
  b.initialize(s.model, s.state, s.c);
  ParticleState p;
  double scale = 0;
  b.read_state(p);
  const auto m0 = momentum(p);
  for (std::uint64_t k = 0; k < 20; ++k) b.advance(k, 0.01);
  b.read_state(p);
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (int a = 0; a < 3; ++a) scale += p.masses[i] * std::fabs(p.velocities[3 * i + a]);
  }
  ASSERT_GT(scale, 1.0);  // the noise really moved the particles
  const auto m = momentum(p);
  for (int a = 0; a < 3; ++a) EXPECT_LT(std::fabs(m[a] - m0[a]), 1e-13 * scale) << "axis " << a;
}

TEST_P(SdpdDim, WendlandKernelConservesMomentumWithNoise) {
  // The SIMD pair block has a separate Wendland C2 branch (F ~ (1-q)^3, sqrt(F) with a sqrt).
  if (GetParam() == 1) GTEST_SKIP() << "Wendland C2 is 2D/3D";
  Scene s = noisy_box(GetParam(), 1.0, GetParam() == 3 ? 7 : 12);
  s.model.kernel = "wendland_c2";
  SdpdBackend b;
  b.initialize(s.model, s.state, s.c);
  ParticleState p;
  b.read_state(p);
  const auto m0 = momentum(p);
  for (std::uint64_t k = 0; k < 20; ++k) b.advance(k, 0.01);
  b.read_state(p);
  double scale = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (int a = 0; a < 3; ++a) scale += p.masses[i] * std::fabs(p.velocities[3 * i + a]);
  }
  ASSERT_GT(scale, 1.0);
  const auto m = momentum(p);
  for (int a = 0; a < 3; ++a) EXPECT_LT(std::fabs(m[a] - m0[a]), 1e-13 * scale) << "axis " << a;
}

TEST_P(SdpdDim, SpeciesMassConservedInPeriodicBox) {
  Scene s = noisy_box(GetParam(), 0.5, GetParam() == 3 ? 7 : 12);
  SdpdBackend b;
  b.initialize(s.model, s.state, s.c);
  auto total = [&] {
    ParticleState p;
    b.read_state(p);
    double t = 0;
    const auto& c = b.concentrations(0);
    for (std::size_t i = 0; i < p.size(); ++i) t += p.masses[i] / p.densities[i] * c[i];
    return t;
  };
  // With the continuity density the volumes m/rho change, so conserve sum_i V_i C_i only up
  // to the density drift; with uniform V (first step from rest) the pairwise flux is exact.
  const double t0 = total();
  for (std::uint64_t k = 0; k < 5; ++k) b.advance(k, 0.01);
  EXPECT_NEAR(total(), t0, 2e-3 * t0);
}

TEST_P(SdpdDim, ThreadCountDoesNotChangeResults) {
#ifdef SADR_HAVE_OPENMP
  // Above kMinParallel particles so that the pair loops really run threaded, and in 1D and
  // 2D above kMinParallelLight so that the per-particle loops do too.
  const int side = GetParam() == 3 ? 12 : GetParam() == 2 ? 130 : 17000;
  Scene s = noisy_box(GetParam(), 1.0, side);
  ASSERT_GT(static_cast<std::int64_t>(s.state.size()),
            GetParam() == 3 ? kMinParallel : kMinParallelLight);
  auto run = [&](int threads) {
    omp_set_num_threads(threads);
    SdpdBackend b;
    b.initialize(s.model, s.state, s.c);
    for (std::uint64_t k = 0; k < 10; ++k) b.advance(k, 0.01);
    ParticleState p;
    b.read_state(p);
    return std::make_pair(p, b.concentrations(0));
  };
  const int max_threads = omp_get_max_threads();
  const auto one = run(1);
  const auto many = run(std::max(2, max_threads));
  const auto three = run(3);
  omp_set_num_threads(max_threads);
  EXPECT_EQ(one.first.positions, many.first.positions);
  EXPECT_EQ(one.first.velocities, many.first.velocities);
  EXPECT_EQ(one.first.densities, many.first.densities);
  EXPECT_EQ(one.second, many.second);
  EXPECT_EQ(one.first.velocities, three.first.velocities);
#else
  GTEST_SKIP() << "built without OpenMP";
#endif
}

TEST_P(SdpdDim, SaveRestoreGivesIdenticalTrajectory) {
  Scene s = noisy_box(GetParam(), 1.0, GetParam() == 3 ? 7 : 12);
  SdpdBackend a;
  a.initialize(s.model, s.state, s.c);
  for (std::uint64_t k = 0; k < 5; ++k) a.advance(k, 0.01);
  const std::string blob = a.save();
  for (std::uint64_t k = 5; k < 12; ++k) a.advance(k, 0.01);
  SdpdBackend b;
  b.initialize(s.model, s.state, s.c);
  b.restore(blob);
  for (std::uint64_t k = 5; k < 12; ++k) b.advance(k, 0.01);
  ParticleState pa, pb;
  a.read_state(pa);
  b.read_state(pb);
  EXPECT_EQ(pa.positions, pb.positions);
  EXPECT_EQ(pa.velocities, pb.velocities);
  EXPECT_EQ(pa.densities, pb.densities);
  EXPECT_EQ(a.concentrations(0), b.concentrations(0));
  EXPECT_EQ(a.time(), b.time());
}

TEST_P(SdpdDim, ZeroTemperatureDrawsNoRandomNumbers) {
  // With k_B T = 0 the seed must not matter at all (no draws), and the run is not trivial.
  Scene s = noisy_box(GetParam(), 0.0, GetParam() == 3 ? 7 : 12);
  auto run = [&](std::uint64_t seed) {
    s.model.seed = seed;
    SdpdBackend b;
    b.initialize(s.model, s.state, s.c);
    for (std::uint64_t k = 0; k < 5; ++k) b.advance(k, 0.01);
    ParticleState p;
    b.read_state(p);
    return p.velocities;
  };
  const auto v1 = run(1), v2 = run(987654321);
  EXPECT_EQ(v1, v2);
  double vmax = 0;
  for (double v : v1) vmax = std::max(vmax, std::fabs(v));
  EXPECT_GT(vmax, 0.0);  // the jittered lattice relaxes: pressure forces act
}

TEST_P(SdpdDim, DifferentSeedsGiveDifferentNoise) {
  Scene s = noisy_box(GetParam(), 1.0, GetParam() == 3 ? 7 : 12);
  auto run = [&](std::uint64_t seed) {
    s.model.seed = seed;
    SdpdBackend b;
    b.initialize(s.model, s.state, s.c);
    b.advance(0, 0.01);
    ParticleState p;
    b.read_state(p);
    return p.velocities;
  };
  EXPECT_NE(run(1), run(2));
}

INSTANTIATE_TEST_SUITE_P(Dims, SdpdDim, ::testing::Values(1, 2, 3));

// Body forces: a uniform periodic box at rest under gravity (x) and a Boussinesq force (y) from a
// stochastic species set through set_concentrations accelerates uniformly: v = a t exactly
// (pressure and viscous forces vanish for a uniform state).
TEST(SdpdBodyForces, GravityAndBoussinesqFromStochasticSpecies) {
  test::LatticeSpec ls;
  ls.dimension = 2;
  ls.n = {10, 10, 1};
  FluidModel m;
  const ParticleState p = test::make_lattice(ls, m.box);
  m.smoothing_length = 3.0;
  m.sound_speed = 10.0;
  m.shear_viscosity = 1.0;
  m.gravity = {0.3, 0, 0};
  m.species.push_back({"X", 0.0, false, {}, {}});  // stochastic: owned by the SSA
  m.boussinesq = {0, 0.5, 1.0, {0, 1, 0}};
  SdpdBackend b;
  b.initialize(m, p, {});
  b.set_concentrations(0, std::vector<double>(p.size(), 2.0));  // a_y = 0.5 (2 - 1)
  for (std::uint64_t k = 0; k < 4; ++k) b.advance(k, 0.05);
  ParticleState s;
  b.read_state(s);
  for (std::size_t i = 0; i < s.size(); ++i) {
    EXPECT_NEAR(s.velocities[3 * i], 0.3 * 0.2, 1e-12);
    EXPECT_NEAR(s.velocities[3 * i + 1], 0.5 * 0.2, 1e-12);
  }
  EXPECT_EQ(b.concentrations(0)[7], 2.0);  // stochastic species are not integrated by the fluid
}

TEST(SdpdReactionSites, DefaultFluidOnlyAndFreeWallsExchange) {
  // 2D channel at rest (k_B T = 0): a production reaction fires on fluid particles only; with a
  // kFree wall the species also diffuses into the wall layers, with kNoFlux it does not.
  for (const auto type : {WallCondition::Type::kNoFlux, WallCondition::Type::kFree}) {
    test::LatticeSpec ls;
    ls.dimension = 2;
    ls.n = {8, 8, 1};
    ls.periodic = {true, false, true};
    ls.wall_layers = 3;
    FluidModel m;
    ParticleState p = test::make_lattice(ls, m.box);
    m.smoothing_length = 3.0;
    m.sound_speed = 10.0;
    m.shear_viscosity = 1.0;
    m.species.push_back({"A", 0.5, true, {type, 0.0}, {}});
    m.reactions.push_back({"make", {}, {{0, 1}}, 1.0, {}, {}});
    SdpdBackend b;
    b.initialize(m, p, {std::vector<double>(p.size(), 0.0)});
    b.advance(0, 0.2);
    const auto& c = b.concentrations(0);
    double wall_max = 0, fluid_min = 1e300;
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.kind(i) == ParticleKind::kWall) {
        wall_max = std::max(wall_max, c[i]);
      } else {
        fluid_min = std::min(fluid_min, c[i]);
      }
    }
    EXPECT_GT(fluid_min, 0.1);
    if (type == WallCondition::Type::kNoFlux) {
      EXPECT_EQ(wall_max, 0.0);
    } else {
      EXPECT_GT(wall_max, 1e-3);
    }
  }
}

TEST(PairNoise, AntisymmetricAndUnitVariance) {
  PairNoise noise{42, NoiseDistribution::kGaussian};
  PairGeometry<3> g{{0.3, -0.2, 0.1}, 0.14, std::sqrt(0.14), 1.0, 1.0 / 0.14};
  PairGeometry<3> gr{{-0.3, 0.2, -0.1}, 0.14, std::sqrt(0.14), 1.0, 1.0 / 0.14};
  std::array<double, 3> fi{}, fj{};
  noise.add(g, 7, 3, 9, 2.0, fi);
  noise.add(gr, 7, 9, 3, 2.0, fj);
  for (int a = 0; a < 3; ++a) EXPECT_EQ(fi[a], -fj[a]);
  // moments of the draws (statistical: 4e5 samples, sd of mean 1.6e-3, of var 2.2e-3; 6 sigma
  // bounds)
  double m = 0, v = 0;
  const int n = 100000;
  for (int k = 0; k < n; ++k) {
    const auto z = noise.draw(static_cast<std::uint64_t>(k), 1, 2);
    for (double x : z) {
      m += x;
      v += x * x;
    }
  }
  m /= 4 * n;
  v = v / (4 * n) - m * m;
  EXPECT_LT(std::fabs(m), 6 * 1.6e-3);
  EXPECT_LT(std::fabs(v - 1.0), 6 * 2.3e-3);
}

TEST(PairNoise, BatchEqualsSingleDrawsAndGaussianMoments) {
  // The SIMD batch (vector lanes + scalar remainder) gives the same numbers as single draws,
  // for neighbours below and above i (key uses min/max).
  const std::uint32_t i = 150;
  std::vector<std::uint32_t> js;
  for (std::uint32_t k = 0; k < 37; ++k) js.push_back(100 + 3 * k);
  std::array<std::vector<float>, 4> z;
  for (auto& v : z) v.resize(js.size());
  const PairNoise single{77, NoiseDistribution::kGaussian};
  pair_noise_numbers(77, 5, i, js.data(), js.size(), NoiseDistribution::kGaussian, z[0].data(),
                     z[1].data(), z[2].data(), z[3].data());
  for (std::size_t k = 0; k < js.size(); ++k) {
    const auto d = single.draw(5, std::min(i, js[k]), std::max(i, js[k]));
    for (int c = 0; c < 4; ++c) EXPECT_EQ(static_cast<double>(z[c][k]), d[c]) << k << " " << c;
  }
  // Moments of 4e5 normals: 4th moment 3 (sd of the mean of z^4: sqrt(96/4e5) = 0.0155) and no
  // correlation inside a Box-Muller pair (sd 1/sqrt(2e5)); 6-sigma bounds.
  double m4 = 0, c01 = 0;
  const int n = 100000;
  for (int k = 0; k < n; ++k) {
    const auto d = single.draw(static_cast<std::uint64_t>(k), 3, 4);
    for (double x : d) m4 += x * x * x * x;
    c01 += d[0] * d[1] + d[2] * d[3];
  }
  EXPECT_LT(std::fabs(m4 / (4 * n) - 3.0), 6 * 0.0155);
  EXPECT_LT(std::fabs(c01 / (2 * n)), 6 / std::sqrt(2.0 * n));
}

}  // namespace
}  // namespace sadr::fluid
