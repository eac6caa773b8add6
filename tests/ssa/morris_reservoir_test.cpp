// SPDX-License-Identifier: MIT
// Morris-extrapolated Dirichlet reservoirs (Model::morris_walls) against exact references: a 1D
// chain between two reservoir walls whose surfaces lie between the wall particles and the first
// fluid voxels. The expected copy numbers of a linear RDME obey exactly the deterministic graph
// equations, so the ensemble means are compared with the steady solution of the (beta-scaled)
// graph; and the linear profile through the means reaches the held value at the wall SURFACE with
// Morris walls, at the wall PARTICLE without.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <map>
#include <vector>

#include "sadr/ssa/nsm_solver.hpp"
#include "ssa_test_support.hpp"

namespace sadr::ssa {
namespace {

/// Steady mean of the free voxels of a one-species diffusion on g with the reservoir voxels
/// `fixed` (voxel -> held count): 0 = sum_j kappa d_ji m_j - kappa (sum_j d_ij) m_i + sources,
/// jumps into a reservoir absorbed. Also the slowest relaxation rate of the free block.
struct Steady {
  std::vector<double> mean;  ///< per voxel (the held count on reservoirs)
  double slowest_rate = 0;   ///< smallest eigenvalue of -M [1/T]
};
Steady steady(const DiffusionGraph& g, double kappa, const std::map<std::uint32_t, double>& fixed) {
  const auto n = static_cast<Eigen::Index>(g.size());
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd s = Eigen::VectorXd::Zero(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (auto e = g.row_start[i]; e < g.row_start[i + 1]; ++e) {
      const double d = kappa * g.edges[e].weight;
      const auto j = static_cast<Eigen::Index>(g.edges[e].target);
      if (fixed.count(static_cast<std::uint32_t>(i))) {
        if (!fixed.count(static_cast<std::uint32_t>(j))) s(j) += d * fixed.at(i);  // emission
        continue;
      }
      m(i, i) -= d;
      if (!fixed.count(static_cast<std::uint32_t>(j))) m(j, i) += d;
    }
  }
  for (const auto& [v, c] : fixed) m(v, v) = 1.0, s(v) = -c;  // m_v = c
  const Eigen::VectorXd x = m.fullPivLu().solve(-s);
  Steady out;
  out.mean.assign(x.data(), x.data() + n);
  std::vector<Eigen::Index> free;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!fixed.count(static_cast<std::uint32_t>(i))) free.push_back(i);
  }
  Eigen::MatrixXd mf(free.size(), free.size());
  for (std::size_t a = 0; a < free.size(); ++a) {
    for (std::size_t b = 0; b < free.size(); ++b) mf(a, b) = m(free[a], free[b]);
  }
  out.slowest_rate = (-mf).eigenvalues().real().minCoeff();
  return out;
}

/// Least-squares line through (x_i, y_i), evaluated at x0, and the weights c_i of y_i in it.
std::vector<double> line_weights(const std::vector<double>& x, double x0) {
  const double n = static_cast<double>(x.size());
  double xbar = 0;
  for (double v : x) xbar += v / n;
  double sxx = 0;
  for (double v : x) sxx += (v - xbar) * (v - xbar);
  std::vector<double> c;
  for (double v : x) c.push_back(1.0 / n + (x0 - xbar) * (v - xbar) / sxx);
  return c;
}

// 12 particles at x = 0.5 .. 11.5 (dx = 1, h = 1.5: nearest neighbours, hop rate 1); walls 0
// and 11 hold W = 200 and 0 molecules. Morris surfaces at x_L = 0.5 + 1/3 (d_j = 1/3, d_i = 2/3:
// beta = 1.5) and x_R = 11.3 (beta = 1.25). Exact steady means: linear, m(x) = W (x_R - x) /
// (x_R - x_L) with Morris walls, W (11.5 - x) / 11 without (ghost-value algebra: a fluid voxel
// at d_i from the surface with beta = (d_i + d_j)/d_i puts the held value exactly on the surface).
// Each of the R = 200 realizations starts empty and is sampled once at T = 120: independent
// Poisson counts of mean m_i(T) (a linear RDME started empty), |m_i(T) - m_i| <= tau =
// ||m||_2 exp(-lambda_1 T) (lambda_1 the slowest rate of the exact graph, about 0.08: tau < 0.03).
// Comparisons: per wall model the 10 fluid means against the exact steady means, and the least-
// squares line through them at both surfaces (Morris) or both wall particles (plain) against
// the held values, each within tau sum|c_i| + z* sqrt(sum c_i^2 m_i / R); 24 in all, Bonferroni
// with alpha_fw = 1e-4. The two models' exact lines at the left surface differ by 6.1 molecules,
// about 13 standard errors of the fitted value: more than 2 z* (asserted), so the check can tell
// the two apart.
TEST(MorrisReservoirs, ChainMeansMatchTheScaledGraphAndReachTheWallValueAtTheSurface) {
  const double h = 1.5, w_left = 200.0;
  const double kappa = 1.0 / (2.0 * lucy_f(1.0, h, 1) / (1.0 + 0.01 * h * h));
  const double x_l = 0.5 + 1.0 / 3.0, x_r = 11.3;
  const int r_count = 200;
  const double t_end = 120.0;
  const double zs = testing::z_star(1e-4, 24);
  ParticleState p = testing::make_lattice(1, 12, 1.0);
  p.kinds[0] = p.kinds[11] = ParticleKind::kWall;
  std::vector<double> xs;
  for (int i = 1; i <= 10; ++i) xs.push_back(p.positions[3 * i]);
  std::map<bool, std::vector<double>> fitted_at_l;  // line value at x_l, per model
  for (const bool morris : {true, false}) {
    SCOPED_TRACE(morris ? "Morris walls" : "plain reservoirs");
    Model m = testing::diffusion_model(testing::make_box(1, 12.0, false), h, kappa);
    m.reservoirs = {{0, w_left, {0}}, {0, 0.0, {11}}};
    if (morris) {
      m.morris_walls = {{{0}, {{x_l, 0, 0}, {1, 0, 0}, 0.0}},
                        {{11}, {{x_r, 0, 0}, {-1, 0, 0}, 0.0}}};
    }
    NsmSolver probe(m, 1);
    probe.update_graph(p);
    const Steady ex = steady(probe.graph(), kappa, {{0, w_left}, {11, 0.0}});
    // the graph equations themselves: linear, through W at the surface (or at the particle)
    const double a = morris ? x_l : 0.5, b = morris ? x_r : 11.5;
    for (int i = 1; i <= 10; ++i) {
      EXPECT_NEAR(ex.mean[i], w_left * (b - xs[i - 1]) / (b - a), 1e-9 * w_left) << "voxel " << i;
    }
    double norm = 0;
    for (int i = 1; i <= 10; ++i) norm += ex.mean[i] * ex.mean[i];
    const double tau = std::sqrt(norm) * std::exp(-ex.slowest_rate * t_end);
    ASSERT_LT(tau, 0.05);

    std::vector<testing::Moments> mom(12);
    for (int r = 0; r < r_count; ++r) {
      NsmSolver s(m, rng::mix_seed(1997, static_cast<std::uint64_t>(r)));
      s.update_graph(p);
      s.advance(t_end);
      ASSERT_EQ(s.counts(0)[0], 200);  // the reservoirs hold
      ASSERT_EQ(s.counts(0)[11], 0);
      for (int i = 1; i <= 10; ++i) mom[i].add(static_cast<double>(s.counts(0)[i]));
    }
    for (int i = 1; i <= 10; ++i) {
      EXPECT_LE(std::abs(mom[i].mean() - ex.mean[i]), tau + zs * std::sqrt(ex.mean[i] / r_count))
          << "voxel " << i << ": SSA mean " << mom[i].mean() << ", exact " << ex.mean[i];
    }
    // The linear interpolant through the means at the points where it should hit the held values.
    auto fit = [&](double x0, double& se, double& bias) {
      const auto c = line_weights(xs, x0);
      double v = 0, var = 0;
      bias = 0;
      for (int i = 1; i <= 10; ++i) {
        v += c[i - 1] * mom[i].mean();
        var += c[i - 1] * c[i - 1] * ex.mean[i] / r_count;
        bias += std::abs(c[i - 1]) * tau;
      }
      se = std::sqrt(var);
      return v;
    };
    double se = 0, bias = 0;
    const double at_left = fit(a, se, bias);
    EXPECT_LE(std::abs(at_left - w_left), bias + zs * se)
        << "line at x = " << a << ": " << at_left << " (held " << w_left << ", se " << se << ")";
    const double at_right = fit(b, se, bias);
    EXPECT_LE(std::abs(at_right), bias + zs * se)
        << "line at x = " << b << ": " << at_right << " (held 0, se " << se << ")";
    const double at_xl = fit(x_l, se, bias);
    fitted_at_l[morris] = {at_xl, se};
    std::printf(
        "%s: line through the SSA means at the wall particle x = 0.5: %.3f, at the "
        "surface x = %.4f: %.3f +- %.3f (held value %.0f)\n",
        morris ? "Morris" : "plain ", fit(0.5, se, bias), x_l, at_xl, fitted_at_l[morris][1],
        w_left);
  }
  // The test's power: the two models' exact lines at the left surface are 2 z* se apart or more.
  const double exact_plain = w_left * (11.5 - x_l) / 11.0;
  const double se_max = std::max(fitted_at_l[true][1], fitted_at_l[false][1]);
  EXPECT_GT(w_left - exact_plain, 2.0 * zs * se_max);
}

}  // namespace
}  // namespace sadr::ssa
