// SPDX-License-Identifier: MIT
// Property: the half-pair path of the SDPD backend (sdpd_half_path.cpp; systems without
// walls, transported species or reactions) against the full-list gather, and its determinism
// (thread count, restarts across neighbour-list rebuilds) and momentum conservation.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "fluid_test_scenes.hpp"
#include "sadr/common/rng.hpp"
#include "sadr/fluid/pair_noise_batch.hpp"
#include "sadr/fluid/pair_terms.hpp"
#include "sadr/fluid/parallel.hpp"
#include "sdpd/sdpd_backend.hpp"
#include "sdpd/sdpd_pair_block.hpp"
#ifdef SADR_HAVE_OPENMP
#include <omp.h>
#endif

namespace sadr::fluid {
namespace {

struct Scene {
  FluidModel model;
  ParticleState state;
};

// Periodic, jittered lattice with a shear wave of amplitude u (large u: list rebuilds).
Scene box(int dim, int side, double u, double kT) {
  Scene s;
  test::LatticeSpec ls;
  ls.dimension = dim;
  ls.n = {side, dim > 1 ? side : 1, dim > 2 ? side : 1};
  s.state = test::make_lattice(ls, s.model.box);
  rng::Xoshiro256 gen(5, 1);
  for (std::size_t i = 0; i < s.state.size(); ++i) {
    for (int a = 0; a < dim; ++a) s.state.positions[3 * i + a] += 0.1 * (gen.uniform() - 0.5);
    s.state.velocities[3 * i] =
        u * std::sin(2.0 * M_PI * s.state.positions[3 * i + dim - 1] / side);
    if (dim > 1)  // across the slabs (last axis) too, so particles change slab
      s.state.velocities[3 * i + dim - 1] =
          u * std::cos(2.0 * M_PI * s.state.positions[3 * i] / side);
    s.state.densities[i] *= 1.0 + 0.01 * (gen.uniform() - 0.5);
  }
  s.model.smoothing_length = dim == 3 ? 2.5 : 3.0;
  s.model.sound_speed = 10.0;
  s.model.shear_viscosity = 1.0;
  s.model.temperature = kT;
  s.model.seed = 99;
  return s;
}

class HalfPairs : public ::testing::TestWithParam<int> {};

// A non-transported species does not change the physics and keeps the half path; a
// deterministic one with zero diffusivity forces the full-list gather: same rates to round-off.
TEST_P(HalfPairs, RatesMatchFullGatherToRoundOff) {
  const int dim = GetParam();
  for (const char* kernel : {"lucy", "wendland_c2"}) {
    if (dim == 1 && std::string(kernel) != "lucy") continue;
    for (const DensityMode mode : {DensityMode::kContinuity, DensityMode::kSummation}) {
      Scene s = box(dim, dim == 3 ? 8 : dim == 2 ? 16 : 64, 0.5, 1.0);
      s.model.kernel = kernel;
      s.model.density_mode = mode;
      SdpdBackend half, full;
      half.initialize(s.model, s.state, {});
      s.model.species.push_back({"A", 0.0, true, {}, {}});
      full.initialize(s.model, s.state, {std::vector<double>(s.state.size(), 1.0)});
      SdpdBackend::Rates rh, rf;
      half.evaluate_current(7, rh);
      full.evaluate_current(7, rf);
      auto close = [](const std::vector<double>& a, const std::vector<double>& b,
                      const char* what) {
        ASSERT_EQ(a.size(), b.size()) << what;
        double scale = 0, err = 0;
        for (std::size_t k = 0; k < a.size(); ++k) {
          scale = std::max(scale, std::fabs(b[k]));
          err = std::max(err, std::fabs(a[k] - b[k]));
        }
        EXPECT_GT(scale, 0.0) << what;
        EXPECT_LE(err, 1e-12 * scale) << what;
      };
      close(rh.acc, rf.acc, "acc");
      close(rh.acc_noise, rf.acc_noise, "acc_noise");
      if (mode == DensityMode::kContinuity) close(rh.drho, rf.drho, "drho");
      EXPECT_NEAR(rh.max_visc_sum, rf.max_visc_sum, 1e-12 * rf.max_visc_sum);
    }
  }
}

TEST_P(HalfPairs, MomentumThreadsAndRestartAcrossListRebuilds) {
  const int dim = GetParam();
  // Above kMinParallel particles so that the slabs really run threaded; u = 3 moves particles
  // past half the skin within the run, so the list (and the slabs) are rebuilt.
  const int side = dim == 3 ? 12 : dim == 2 ? 40 : 2000;
  const Scene s = box(dim, side, 3.0, 1.0);
  ASSERT_GT(static_cast<std::int64_t>(s.state.size()), kMinParallel);
  auto run = [&](int threads, bool restart) {
#ifdef SADR_HAVE_OPENMP
    omp_set_num_threads(threads);
#else
    (void)threads;
#endif
    SdpdBackend b;
    b.initialize(s.model, s.state, {});
    for (std::uint64_t k = 0; k < 5; ++k) b.advance(k, 0.01);  // list built at step 0 only
    if (restart) {
      const std::string blob = b.save();
      SdpdBackend c;
      c.initialize(s.model, s.state, {});
      c.restore(blob);
      for (std::uint64_t k = 5; k < 16; ++k) c.advance(k, 0.01);
      ParticleState p;
      c.read_state(p);
      return p;
    }
    for (std::uint64_t k = 5; k < 16; ++k) b.advance(k, 0.01);
    ParticleState p;
    b.read_state(p);
    return p;
  };
#ifdef SADR_HAVE_OPENMP
  [[maybe_unused]] const int max_threads = omp_get_max_threads();
#else
  [[maybe_unused]] const int max_threads = 1;
#endif
  const ParticleState one = run(1, false);
  const ParticleState two = run(2, false);
  const ParticleState three = run(3, true);
#ifdef SADR_HAVE_OPENMP
  omp_set_num_threads(max_threads);
#endif
  EXPECT_EQ(one.positions, two.positions);
  EXPECT_EQ(one.velocities, two.velocities);
  EXPECT_EQ(one.densities, two.densities);
  EXPECT_EQ(one.positions, three.positions);
  EXPECT_EQ(one.velocities, three.velocities);
  EXPECT_EQ(one.densities, three.densities);
  // the run crossed list rebuilds
  double moved = 0;
  for (std::size_t i = 0; i < one.size(); ++i) {
    double d[3];
    for (int a = 0; a < 3; ++a) d[a] = one.positions[3 * i + a] - s.state.positions[3 * i + a];
    PeriodicBox(s.model.box).minimum_image(d);
    moved = std::max(moved, std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
  }
  EXPECT_GT(moved, 0.5 * 0.15 * s.model.smoothing_length);
  double m0[3] = {0, 0, 0}, m1[3] = {0, 0, 0}, scale = 0;
  for (std::size_t i = 0; i < one.size(); ++i) {
    for (int a = 0; a < 3; ++a) {
      m0[a] += s.state.masses[i] * s.state.velocities[3 * i + a];
      m1[a] += one.masses[i] * one.velocities[3 * i + a];
      scale += one.masses[i] * std::fabs(one.velocities[3 * i + a]);
    }
  }
  for (int a = 0; a < 3; ++a) EXPECT_LT(std::fabs(m1[a] - m0[a]), 1e-13 * scale) << "axis " << a;
}

INSTANTIATE_TEST_SUITE_P(Dims, HalfPairs, ::testing::Values(1, 2, 3));

TEST(PairNoiseBatch, EqualsSingleDrawsForEveryLanePadding) {
  // pair_noise_numbers dispatches to the avx512f / avx2 / default clone of the CPU (16-lane
  // padding inside 64-pair chunks); every size must give the scalar PairNoise numbers.
  rng::Xoshiro256 gen(11, 2);
  for (const NoiseDistribution dist : {NoiseDistribution::kGaussian, NoiseDistribution::kUniform}) {
    const PairNoise single{0xABCDEF0123ULL, dist};
    for (std::size_t n : {1u, 7u, 16u, 17u, 63u, 64u, 65u, 150u}) {
      std::vector<std::uint32_t> js(n);
      for (auto& j : js) j = static_cast<std::uint32_t>(gen.uniform() * 4e9);
      const auto i = static_cast<std::uint32_t>(gen.uniform() * 4e9);
      const std::uint64_t step = (std::uint64_t{12345} << 16) | 3;
      std::array<std::vector<float>, 4> z;
      for (auto& v : z) v.assign(n + 1, -7.0f);  // one guard value past the end
      pair_noise_numbers(0xABCDEF0123ULL, step, i, js.data(), n, dist, z[0].data(), z[1].data(),
                         z[2].data(), z[3].data());
      for (std::size_t k = 0; k < n; ++k) {
        const auto d = single.draw(step, std::min(i, js[k]), std::max(i, js[k]));
        for (int c = 0; c < 4; ++c) {
          ASSERT_EQ(static_cast<double>(z[static_cast<std::size_t>(c)][k]), d[c])
              << "n " << n << " k " << k << " word " << c;
        }
      }
      for (const auto& v : z) EXPECT_EQ(v[n], -7.0f) << "wrote past n = " << n;
    }
  }
}

// The half path batches several particles i per block (2D): the per-lane forms must give, for
// every pair, the bits of the one-particle forms (so the batching cannot change a trajectory).
TEST(PairNoiseBatch, LanesEqualOneParticleCalls) {
  rng::Xoshiro256 gen(13, 4);
  for (const NoiseDistribution dist : {NoiseDistribution::kGaussian, NoiseDistribution::kUniform}) {
    // 5 particles with 0, 3, 12, 17 and 40 pairs: lane vectors mix particles and padding
    const std::array<std::size_t, 5> counts{0, 3, 12, 17, 40};
    std::vector<std::uint32_t> is, js;
    for (std::size_t p = 0; p < counts.size(); ++p) {
      for (std::size_t k = 0; k < counts[p]; ++k) {
        is.push_back(static_cast<std::uint32_t>(1000 + p));
        js.push_back(static_cast<std::uint32_t>(gen.uniform() * 4e9));
      }
    }
    const std::size_t n = is.size();
    const std::uint64_t step = (std::uint64_t{77} << 16) | 1;
    std::array<std::vector<float>, 4> z;
    for (auto& v : z) v.assign(n, 0.0f);
    pair_noise_numbers_lanes(5, step, is.data(), js.data(), n, dist, z[0].data(), z[1].data(),
                             z[2].data(), z[3].data());
    std::size_t k0 = 0;
    for (std::size_t p = 0; p < counts.size(); ++p) {
      std::array<std::vector<float>, 4> w;
      for (auto& v : w) v.assign(counts[p] + 1, 0.0f);
      pair_noise_numbers(5, step, static_cast<std::uint32_t>(1000 + p), js.data() + k0, counts[p],
                         dist, w[0].data(), w[1].data(), w[2].data(), w[3].data());
      for (std::size_t k = 0; k < counts[p]; ++k) {
        for (std::size_t c = 0; c < 4; ++c) ASSERT_EQ(z[c][k0 + k], w[c][k]) << p << " " << k;
      }
      k0 += counts[p];
    }
  }
}

TEST(SdpdPairBlock, LanesEqualOneParticleCalls) {
  rng::Xoshiro256 gen(17, 5);
  for (const bool lucy : {true, false}) {
    SdpdPairParams pp;
    pp.inv_h = 1.0 / 3.0;
    pp.f_coef = 0.7;
    pp.sqrt_f_coef = std::sqrt(0.7);
    pp.lucy = lucy;
    pp.friction = 1.6;
    pp.delta_h_c0 = 3.0;
    pp.eps_h2 = 0.09;
    pp.noise = true;
    pp.noise_amp = 0.2;
    const std::array<std::size_t, 4> counts{5, 12, 1, 23};
    std::size_t n = 0;
    for (auto c : counts) n += c;
    SdpdPairBlock lanes;
    lanes.reserve(n);
    std::vector<SdpdPairI> pis;
    for (std::size_t p = 0, k = 0; p < counts.size(); ++p) {
      const SdpdPairI pi{static_cast<std::uint32_t>(50 + 7 * p), 1 + gen.uniform(),
                         0.9 + 0.2 * gen.uniform(), 1 + 0.01 * gen.uniform(), 0.95 + gen.uniform()};
      pis.push_back(pi);
      for (std::size_t e = 0; e < counts[p]; ++e, ++k) {
        lanes.j[k] = static_cast<std::uint32_t>(gen.uniform() * 100);
        double r2 = 0;
        for (int a = 0; a < 3; ++a) {
          lanes.x[a][k] = 3.4 * (gen.uniform() - 0.5);
          lanes.v[a][k] = gen.uniform() - 0.5;
          r2 += lanes.x[a][k] * lanes.x[a][k];
        }
        lanes.r2[k] = std::min(r2, 8.9);
        for (auto* q : {&lanes.pd2_j, &lanes.inv_nd_j, &lanes.m_j, &lanes.vol_j, &lanes.rho_j,
                        &lanes.sqrt_inv_nd_j})
          (*q)[k] = 0.9 + 0.2 * gen.uniform();
        lanes.i[k] = pi.i;
        lanes.pd2_i[k] = pi.pd2;
        lanes.inv_nd_i[k] = pi.inv_nd;
        lanes.rho_i[k] = pi.rho;
        lanes.sqrt_inv_nd_i[k] = pi.sqrt_inv_nd;
      }
    }
    SdpdPairBlock one = lanes;  // same inputs, evaluated particle by particle
    sdpd_pair_block_lanes<3>(pp, n, lanes);
    std::size_t k0 = 0;
    for (std::size_t p = 0; p < counts.size(); ++p) {
      SdpdPairBlock part;
      part.reserve(counts[p]);
      auto copy = [&](const std::vector<double>& from, std::vector<double>& to) {
        std::copy_n(from.begin() + static_cast<std::ptrdiff_t>(k0), counts[p], to.begin());
      };
      std::copy_n(one.j.begin() + static_cast<std::ptrdiff_t>(k0), counts[p], part.j.begin());
      for (int a = 0; a < 3; ++a) {
        copy(one.x[a], part.x[a]);
        copy(one.v[a], part.v[a]);
      }
      copy(one.r2, part.r2);
      copy(one.pd2_j, part.pd2_j);
      copy(one.inv_nd_j, part.inv_nd_j);
      copy(one.m_j, part.m_j);
      copy(one.vol_j, part.vol_j);
      copy(one.rho_j, part.rho_j);
      copy(one.sqrt_inv_nd_j, part.sqrt_inv_nd_j);
      sdpd_pair_block<3>(pp, pis[p], counts[p], part);
      for (std::size_t k = 0; k < counts[p]; ++k) {
        for (int a = 0; a < 3; ++a) ASSERT_EQ(lanes.force[a][k0 + k], part.force[a][k]);
        ASSERT_EQ(lanes.drho[k0 + k], part.drho[k]);
        ASSERT_EQ(lanes.f[k0 + k], part.f[k]);
        ASSERT_EQ(lanes.amp[k0 + k], part.amp[k]);
        ASSERT_EQ(lanes.amp_r[k0 + k], part.amp_r[k]);
      }
      k0 += counts[p];
    }
  }
}

}  // namespace
}  // namespace sadr::fluid
