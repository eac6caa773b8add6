// SPDX-License-Identifier: MIT
/// \file adaptive_cases.hpp
/// The error cases of the adaptive SSA (docs/method.md "Adaptive SSA"), shared by the default
/// suite (adaptive_test.cpp, one or two tolerances) and the validation sweep
/// (adaptive_validation_test.cpp, four decades): ensembles of the adaptive solver against the
/// exact mean and variance of a first-order RDME (linear_exact.hpp, expm).
///
/// Measure per comparison point (voxel x time) with exact mean m and variance v, over R runs:
/// the relative bias of the mean b_m = (mean - m) / m and of the variance b_v = (s^2 - v) / v,
/// and their standard errors (sqrt(v / R) / m and the sample-fourth-moment SE of s^2, / v).
/// The pass rule is |b| <= eps + z* SE (Bonferroni z* at the stated family-wise rate): the
/// bias must stay below the tolerance up to the sampling noise.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "linear_exact.hpp"
#include "sadr/ssa/nsm_solver.hpp"
#include "ssa_test_support.hpp"

namespace sadr::ssa::testing {

/// Mean, variance and the standard errors of both from the first four power sums.
struct Sample4 {
  double n = 0, s1 = 0, s2 = 0, s3 = 0, s4 = 0;
  void add(double x) { n += 1, s1 += x, s2 += x * x, s3 += x * x * x, s4 += x * x * x * x; }
  [[nodiscard]] double mean() const { return s1 / n; }
  [[nodiscard]] double var() const { return (s2 - s1 * s1 / n) / (n - 1); }
  /// Fourth central moment (plug-in).
  [[nodiscard]] double mu4() const {
    const double m = mean();
    return s4 / n - 4 * m * s3 / n + 6 * m * m * s2 / n - 3 * m * m * m * m;
  }
  [[nodiscard]] double se_var() const {
    const double v = var();
    return std::sqrt(std::max(0.0, (mu4() - v * v * (n - 3) / (n - 1)) / n));
  }
};

struct CaseResult {
  double eps = 0;
  int points = 0;            ///< comparison points (voxel x time with m >= min_mean)
  double max_bias_mean = 0;  ///< max |b_m| (relative)
  double max_bias_var = 0;   ///< max |b_v| (relative)
  double mean_se = 0;        ///< the SE of b_m at the point of max |b_m|
  double var_se = 0;         ///< the SE of b_v at the point of max |b_v|
  double max_excess = 0;     ///< max (|b| - eps) / SE over both (<= z* to pass)
  double mean_z_mean = 0;    ///< average signed z of b_m over the points (sign check)
  double mean_z_var = 0;     ///< average signed z of b_v over the points
  std::string where_mean;    ///< the point of max |b_m|: voxel, time, exact mean
  std::string where_var;     ///< the point of max |b_v|
  std::uint64_t events = 0;  ///< exact events, summed over the ensemble
  std::uint64_t leaped = 0;  ///< molecules leaped, summed over the ensemble
};

/// A first-order case: graph from `particles`, one species of diffusivity `kappa`, decay k,
/// births b_i = birth V_i, initial counts x0; compared at `times` where the exact mean >= min_mean.
struct LinearCase {
  Model model;
  ParticleState particles;
  double kappa = 0, decay = 0, birth = 0;
  std::vector<std::int64_t> x0;
  std::vector<double> times;
  double min_mean = 100;
};

/// Case (c): 20 voxels on a line with unit hop rate to each neighbour (h = 1.5 dx, V = 1),
/// reflecting ends, `height` molecules in each of the first 10 voxels: a step relaxing by
/// pure diffusion (exact mean from dm/dt = M m).
inline LinearCase lattice_step(std::int64_t height) {
  LinearCase c;
  const double h = 1.5;
  const double reg = 1.0 / (1.0 + 0.01 * h * h);
  c.kappa = 1.0 / (2.0 * lucy_f(1.0, h, 1) * reg);
  c.model = diffusion_model(make_box(1, 20.0, false), h, c.kappa);
  c.particles = make_lattice(1, 20, 1.0);
  c.x0.assign(20, 0);
  for (int i = 0; i < 10; ++i) c.x0[i] = height;
  c.times = {0.5, 2.0};
  return c;
}

/// Case (a): the irregular 2D graph of LinearNetwork.IrregularGraphMeanAndVarianceMatchExpm
/// (jittered 5 x 5 lattice, masses +-30 %, walled box, kappa 0.3, A -> 0 at 0.2, 0 -> A at
/// 2 per unit volume) with `x0` molecules released in voxel 12.
inline LinearCase irregular_release(std::int64_t x0) {
  LinearCase c;
  c.kappa = 0.3, c.decay = 0.2, c.birth = 2.0;
  c.model = diffusion_model(make_box(2, 5.0, false), 1.7, c.kappa);
  c.model.reactions = {{"decay", {{0, 1}}, {}, c.decay, {}, {}},
                       {"birth", {}, {{0, 1}}, c.birth, {}, {}}};
  c.particles = make_lattice(2, 5, 1.0, 0.3, 0.3, 11);
  c.x0.assign(25, 0);
  c.x0[12] = x0;
  c.times = {0.5, 2.0};
  return c;
}

/// R runs of `c` with the given method; bias against the exact moments.
inline CaseResult run_linear_case(LinearCase c, SsaMethod method, double eps, int runs,
                                  std::uint64_t seed) {
  c.model.method = method;
  c.model.tolerance = eps;
  const std::size_t n = c.particles.size();
  std::vector<std::vector<Sample4>> mom(c.times.size(), std::vector<Sample4>(n));
  CaseResult out;
  out.eps = eps;
  DiffusionGraph graph;
  for (int r = 0; r < runs; ++r) {
    NsmSolver s(c.model, rng::mix_seed(seed, static_cast<std::uint64_t>(r)));
    s.update_graph(c.particles);
    if (r == 0) graph = s.graph();
    s.set_counts(0, c.x0);
    for (std::size_t t = 0; t < c.times.size(); ++t) {
      s.advance(c.times[t]);
      const auto x = s.counts(0);
      for (std::size_t i = 0; i < n; ++i) mom[t][i].add(static_cast<double>(x[i]));
    }
    out.events += s.events();
    out.leaped += s.leaped_molecules();
  }
  std::vector<double> b(n), x0(n);
  for (std::size_t i = 0; i < n; ++i) {
    b[i] = c.birth * graph.volume[i];
    x0[i] = static_cast<double>(c.x0[i]);
  }
  for (std::size_t t = 0; t < c.times.size(); ++t) {
    const LinearExact ex = linear_exact(graph, c.kappa, c.decay, b, x0, c.times[t]);
    for (std::size_t i = 0; i < n; ++i) {
      const double m = ex.mean(static_cast<Eigen::Index>(i));
      const double v = ex.var(static_cast<Eigen::Index>(i));
      if (m < c.min_mean) continue;
      ++out.points;
      const Sample4& s = mom[t][i];
      const double bm = (s.mean() - m) / m, se_m = std::sqrt(v / runs) / m;
      const double bv = (s.var() - v) / v, se_v = s.se_var() / v;
      out.mean_z_mean += bm / se_m;
      out.mean_z_var += bv / se_v;
      const std::string at = "voxel " + std::to_string(i) + " t " + std::to_string(c.times[t]) +
                             " m " + std::to_string(m);
      if (std::abs(bm) > out.max_bias_mean) {
        out.max_bias_mean = std::abs(bm), out.mean_se = se_m, out.where_mean = at;
      }
      if (std::abs(bv) > out.max_bias_var) {
        out.max_bias_var = std::abs(bv), out.var_se = se_v, out.where_var = at;
      }
      out.max_excess =
          std::max({out.max_excess, (std::abs(bm) - eps) / se_m, (std::abs(bv) - eps) / se_v});
    }
  }
  if (out.points > 0) out.mean_z_mean /= out.points, out.mean_z_var /= out.points;
  return out;
}

inline std::string describe(const CaseResult& r) {
  return "eps=" + std::to_string(r.eps) + " points=" + std::to_string(r.points) +
         " max|bias mean|=" + std::to_string(r.max_bias_mean) + " (se " +
         std::to_string(r.mean_se) + ", " + r.where_mean +
         ") max|bias var|=" + std::to_string(r.max_bias_var) + " (se " + std::to_string(r.var_se) +
         ", " + r.where_var + ") max excess z=" + std::to_string(r.max_excess) +
         " mean signed z (mean, var)=" + std::to_string(r.mean_z_mean) + ", " +
         std::to_string(r.mean_z_var) + " events=" + std::to_string(r.events) +
         " leaped=" + std::to_string(r.leaped);
}

}  // namespace sadr::ssa::testing
