// SPDX-License-Identifier: MIT
/// Unit tests of the tDPD half-pair path: pow_unit against std::pow, the half list against the
/// O(N^2) reference (every pair exactly once, within 3 consecutive slabs), and the pair forces,
/// fluxes and densities of a random many-particle state against a direct O(N^2) sum of the
/// li2015 formulas with the documented noise numbers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

#include "sadr/common/rng.hpp"
#include "sadr/fluid/kernel.hpp"
#include "sadr/fluid/pair_noise_batch.hpp"
#include "tdpd/tdpd_backend.hpp"
#include "tdpd/tdpd_cells.hpp"
#include "tdpd/tdpd_pair_block.hpp"

namespace sadr::fluid {
namespace {

TEST(TdpdPairs, PowUnitMatchesStdPow) {
  for (const double p : {0.205, 0.1, 0.37, 0.75, 1.7}) {
    double worst = 0.0;  // relative error / (1 + |p ln x|), the documented bound / 2.2e-16
    for (int k = 0; k <= 20000; ++k) {
      // linear in (0, 1] and logarithmic down to 2^-53 (the smallest 1 - r/r_c > 0)
      for (const double x : {k / 20000.0, std::exp2(-53.0 * k / 20000.0)}) {
        if (x == 0.0) continue;
        const double ref = std::pow(x, p);
        const double rel = std::abs(tdpd::pow_unit(x, p) - ref) / ref;
        worst = std::max(worst, rel / (1.0 + std::abs(p * std::log(x))));
      }
    }
    EXPECT_LT(worst, 3e-16) << "p = " << p;
  }
  EXPECT_EQ(tdpd::pow_unit(0.0, 0.205), 0.0);
  EXPECT_EQ(tdpd::pow_unit(1.0, 0.205), 1.0);
}

std::vector<double> random_positions(const Box& box, std::size_t n, std::uint64_t seed) {
  const rng::CounterRng g{seed};
  std::vector<double> x(3 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const auto u = g.uniform2(rng::Purpose::kTest, 0, static_cast<std::uint32_t>(i), 0);
    const auto w = g.uniform2(rng::Purpose::kTest, 1, static_cast<std::uint32_t>(i), 0);
    const double t[3] = {u[0], u[1], w[0]};
    for (int a = 0; a < box.dimension; ++a)
      x[3 * i + a] = box.lo[a] + t[a] * box.length(a) * (1.0 - 1e-12);
  }
  return x;
}

void expect_half_list_exact(const Box& box, double cutoff, std::size_t n) {
  const auto x = random_positions(box, n, 17);
  tdpd::HalfList h;
  tdpd::build_half_list(PeriodicBox(box), cutoff, x, h);
  const NeighborList ref = brute_force_neighbors(box, cutoff, x);
  std::set<std::pair<std::uint32_t, std::uint32_t>> want, got;
  for (std::uint32_t i = 0; i < n; ++i) {
    for (const std::uint32_t j : ref.of(i)) want.insert({std::min(i, j), std::max(i, j)});
  }
  std::vector<std::uint32_t> slab(n, 0);
  ASSERT_EQ(h.slabs.start.size(), h.slabs.count + 1);
  ASSERT_EQ(h.slabs.start.back(), n);
  for (std::uint32_t s = 0; s < h.slabs.count; ++s) {
    for (std::uint32_t k = h.slabs.start[s]; k < h.slabs.start[s + 1]; ++k)
      slab[h.slabs.members[k]] = s;
  }
  std::vector<std::uint32_t> members = h.slabs.members;
  std::sort(members.begin(), members.end());
  for (std::uint32_t i = 0; i < n; ++i) ASSERT_EQ(members[i], i) << "slab members: a permutation";
  std::size_t entries = 0;
  for (std::uint32_t i = 0; i < n; ++i) {
    for (const std::uint32_t j : h.list.of(i)) {
      ++entries;
      EXPECT_TRUE(got.insert({std::min(i, j), std::max(i, j)}).second)
          << "pair " << i << "," << j << " listed twice";
      // j lies 0..2 slabs ahead of i (mod the count on a periodic slab axis)
      std::uint32_t ds = slab[j] - slab[i];
      if (box.periodic[box.dimension - 1] && slab[j] < slab[i]) ds += h.slabs.count;
      EXPECT_LE(ds, 2U) << "pair " << i << "," << j;
      if (ds == 0) {
        EXPECT_GT(j, i);
      }
    }
  }
  EXPECT_EQ(got, want);
  EXPECT_EQ(entries, want.size());
}

TEST(TdpdPairs, HalfListListsEveryPairOnce) {
  Box b3;
  b3.dimension = 3;
  b3.hi = {8.0, 7.0, 9.5};
  b3.periodic = {true, true, true};
  expect_half_list_exact(b3, 2.05, 400);  // 9 slabs, 7 cells on x: no aliasing
  Box walled = b3;
  walled.periodic = {true, false, false};
  expect_half_list_exact(walled, 2.05, 400);
  Box small = b3;  // 4 cells per axis: the +-2 cell offsets alias; one slab
  small.hi = {4.2, 4.3, 4.4};
  expect_half_list_exact(small, 2.05, 300);
  Box b2;
  b2.dimension = 2;
  b2.hi = {10.0, 12.0, 1.0};
  b2.periodic = {true, true, false};
  expect_half_list_exact(b2, 1.3, 300);
  Box b1;
  b1.dimension = 1;
  b1.hi = {30.0, 1.0, 1.0};
  b1.periodic = {true, false, false};
  expect_half_list_exact(b1, 1.0, 200);
}

TEST(TdpdPairs, ForcesFluxesAndDensitiesMatchADirectSum) {
  FluidModel m;
  m.box.dimension = 3;
  m.box.hi = {7.0, 7.5, 8.0};
  m.box.periodic = {true, true, true};
  m.smoothing_length = 1.58;
  m.reference_density = 4.0;
  m.temperature = 1.0;
  m.seed = 4242;
  for (const char* name : {"A", "B"}) {
    SpeciesSpec s;
    s.def.name = name;
    s.def.diffusivity = 0.4;
    m.species.push_back(s);
  }
  const std::size_t n = 400;
  ParticleState st;
  st.dimension = 3;
  st.resize(n, true);
  st.positions = random_positions(m.box, n, 5);
  const auto vel = random_positions(m.box, n, 6);
  std::vector<std::vector<double>> conc(2, std::vector<double>(n));
  for (std::size_t i = 0; i < n; ++i) {
    for (int a = 0; a < 3; ++a) st.velocities[3 * i + a] = vel[3 * i + a] / 4.0 - 1.0;
    st.masses[i] = 1.0;
    st.densities[i] = 4.0;
    conc[0][i] = std::sin(st.positions[3 * i]);
    conc[1][i] = st.positions[3 * i + 2] > 4.0 ? 1.0 : 0.0;
  }
  TdpdParameters prm;
  prm.r_cc = 1.2;
  TdpdBackend b;
  b.set_parameters(prm);
  b.initialize(m, st, conc);
  const std::uint64_t step = 12;
  const double dt = 0.01;
  std::vector<double> f;
  std::vector<std::vector<double>> q;
  b.evaluate_current(step, dt, f, q);
  ParticleState out;
  b.read_state(out);

  // Direct sum over all i != j of li2015 eqs 3-6; noise: word pair 0 (z0) of the core batch
  // generator at step = noise_step << 16 (the regular evaluation of a step).
  const PeriodicBox pb(m.box);
  const Kernel kernel(KernelType::kLucy, 3, m.smoothing_length);
  const double rc = m.smoothing_length, sigma_dt = std::sqrt(2.0 * prm.gamma) / std::sqrt(dt);
  std::vector<double> fr(3 * n, 0.0), rho(n, kernel.w0());
  std::vector<std::vector<double>> qr(2, std::vector<double>(n, 0.0));
  for (std::uint32_t i = 0; i < n; ++i) {
    for (std::uint32_t j = 0; j < n; ++j) {
      if (i == j) continue;
      double d[3], dv[3];
      for (int a = 0; a < 3; ++a) {
        d[a] = st.positions[3 * i + a] - st.positions[3 * j + a];
        dv[a] = st.velocities[3 * i + a] - st.velocities[3 * j + a];
      }
      pb.minimum_image(d);
      const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      if (r >= rc) continue;
      float z[4];
      pair_noise_numbers(m.seed, step << 16, i, &j, 1, NoiseDistribution::kGaussian, &z[0], &z[1],
                         &z[2], &z[3]);
      const double wc = 1.0 - r / rc, wr = std::pow(wc, 0.5 * prm.s1);
      const double ev = (d[0] * dv[0] + d[1] * dv[1] + d[2] * dv[2]) / r;
      const double fmag = prm.a * wc - prm.gamma * wr * wr * ev + sigma_dt * wr * z[0];
      for (int a = 0; a < 3; ++a) fr[3 * i + a] += fmag * d[a] / r;
      rho[i] += kernel.w(r);
      if (r < prm.r_cc) {
        const double w = (1.0 - r / prm.r_cc) * (1.0 - r / prm.r_cc);
        for (int s = 0; s < 2; ++s) qr[s][i] += 0.4 * w * (conc[s][j] - conc[s][i]);
      }
    }
  }
  double p[3] = {0, 0, 0};
  for (std::size_t i = 0; i < n; ++i) {
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(f[3 * i + a], fr[3 * i + a], 1e-9 * (1.0 + std::abs(fr[3 * i + a])))
          << "particle " << i << " axis " << a;
      p[a] += f[3 * i + a];
    }
    EXPECT_NEAR(out.densities[i], rho[i], 1e-12 * rho[i]) << "particle " << i;
    for (int s = 0; s < 2; ++s) EXPECT_NEAR(q[s][i], qr[s][i], 1e-12) << "particle " << i;
  }
  for (int a = 0; a < 3; ++a) EXPECT_LT(std::abs(p[a]), 1e-10) << "total force, axis " << a;
}

}  // namespace
}  // namespace sadr::fluid
