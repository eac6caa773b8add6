// SPDX-License-Identifier: MIT
// Property: a stochastic tracer carried by a uniform prescribed flow. The "prescribed" backend
// moves a periodic 2D lattice with u = U; the SSA (NsmSolver) diffuses N0 molecules released at
// one particle on the particle graph, coupled by Lie splitting per coupling step as the
// orchestrator does (fluid advance, graph update at the new positions, SSA advance). A uniform
// flow translates the lattice rigidly, so the graph keeps its shape and both moments are exact in
// expectation: mean displacement U t, mean square displacement about U t 2 d kappa_eff t with
// kappa_eff = ratio kappa (refs/sph_consistency.csv; docs/ssa-core.md).
// Statistics: the molecules are independent walkers; per sample time, z = (estimate - exact) / SE
// for the d components of the mean and for the MSD (SE from the sample). PASS iff every
// |z| <= z*, z* the Bonferroni value for M = 3 times x (d + 1) = 9 statistics at a family-wise
// false-failure rate alpha_fw = 1e-4.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "sadr/fluid/builtin_backends.hpp"
#include "sadr/ssa/nsm_solver.hpp"
#include "ssa_test_support.hpp"

namespace sadr {
namespace {

TEST(PrescribedTracer, UniformFlowMeanIsUtAndVarianceIsTwoDKappaEffT) {
  constexpr int dim = 2, n = 48;
  const double dx = 1.0, h = 3.0 * dx, kappa = 1.0, len = n * dx;
  const double u[2] = {0.6, -0.3};
  const double kappa_eff = ssa::testing::kappa_ratio(dim, 0.01, h / dx) * kappa;
  const Box box = ssa::testing::make_box(dim, len, true);
  const ParticleState lattice = ssa::testing::make_lattice(dim, n, dx);

  fluid::FluidModel fm;
  fm.box = box;
  fm.smoothing_length = h;
  fm.backend_parameters = {{"field", 0}, {"ux", u[0]}, {"uy", u[1]}};
  fluid::BackendRegistry registry;
  fluid::register_builtin_backends(registry);
  auto flow = registry.create("prescribed");
  flow->initialize(fm, lattice, {});

  ssa::NsmSolver ssa(ssa::testing::diffusion_model(box, h, kappa), 2026);
  ssa.update_graph(lattice);
  const std::size_t src = static_cast<std::size_t>(n / 2) * n + n / 2;  // near the centre
  const std::int64_t n0 = 100000;
  std::vector<std::int64_t> x0(lattice.size(), 0);
  x0[src] = n0;
  ssa.set_counts(0, x0);

  const double zs = ssa::testing::z_star(1e-4, 3 * (dim + 1));
  const double dt = 0.25;  // coupling step
  std::uint64_t step = 0;
  double t = 0;
  ParticleState now;
  // per-axis RMS spread 1.5, 2.5, 3.5 dx: the tracer stays well inside half a box (24 dx)
  for (const int steps : {5, 13, 25}) {
    for (; step < static_cast<std::uint64_t>(steps); ++step) {
      flow->advance(step, dt);
      t += dt;
      flow->read_state(now);
      ssa.update_graph(now);
      ssa.advance(t);
    }
    double m1[2] = {0, 0}, m2 = 0, m4 = 0, s1[2] = {0, 0};
    std::int64_t total = 0;
    for (std::size_t i = 0; i < now.size(); ++i) {
      const double c = static_cast<double>(ssa.counts(0)[i]);
      if (c == 0) continue;
      double d[2], r2 = 0;
      for (int a = 0; a < dim; ++a) {
        d[a] = now.positions[3 * i + a] - lattice.positions[3 * src + a];  // displacement
        d[a] -= len * std::round(d[a] / len);
        m1[a] += c * d[a];
        s1[a] += c * d[a] * d[a];
        const double e = d[a] - u[a] * t;  // about the exact mean
        r2 += e * e;
      }
      m2 += c * r2;
      m4 += c * r2 * r2;
      total += ssa.counts(0)[i];
    }
    ASSERT_EQ(total, n0);
    const double nn = static_cast<double>(n0);
    for (int a = 0; a < dim; ++a) {
      const double mean = m1[a] / nn, se = std::sqrt((s1[a] / nn - mean * mean) / nn);
      const double z = (mean - u[a] * t) / se;
      std::printf("RESULT prescribed tracer t=%.2f axis=%d mean=%.5f exact=%.5f z=%.2f\n", t, a,
                  mean, u[a] * t, z);
      EXPECT_LE(std::abs(z), zs) << "mean displacement, axis " << a << ", t = " << t;
    }
    const double msd = m2 / nn, se = std::sqrt((m4 / nn - msd * msd) / nn);
    const double expect = 2 * dim * kappa_eff * t;
    const double z = (msd - expect) / se;
    std::printf("RESULT prescribed tracer t=%.2f msd=%.5f exact=%.5f z=%.2f (z*=%.2f)\n", t, msd,
                expect, z, zs);
    EXPECT_LE(std::abs(z), zs) << "variance about U t, t = " << t;
  }
}

}  // namespace
}  // namespace sadr
