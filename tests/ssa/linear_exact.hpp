// SPDX-License-Identifier: MIT
/// \file linear_exact.hpp
/// Exact mean and variance of a first-order RDME on a fixed graph (refs/README.md
/// section 6, Jahnke & Huisinga 2007), computed with Eigen's matrix exponential:
///   dm/dt = M m + s,  M = R^T - diag(sum_j d_ij) - k I,  s_i = b_i,
///   X(t) = sum_j Multinomial(x0_j, P(t)[:, j]) + Poisson(lambda(t)), P = expm(M t).
#pragma once

#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>
#include <vector>

#include "sadr/ssa/diffusion_graph.hpp"

namespace sadr::ssa::testing {

struct LinearExact {
  Eigen::VectorXd mean, var, lambda;
  Eigen::MatrixXd p;  ///< P(t)
};

/// @param g graph with weights D_ij; kappa diffusivity; k decay [1/T]; b births per voxel [1/T]
inline LinearExact linear_exact(const DiffusionGraph& g, double kappa, double k,
                                const std::vector<double>& b, const std::vector<double>& x0,
                                double t) {
  const auto n = static_cast<Eigen::Index>(g.size());
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (auto e = g.row_start[i]; e < g.row_start[i + 1]; ++e) {
      const double d = kappa * g.edges[e].weight;
      m(g.edges[e].target, i) += d;  // inflow to j from i
      m(i, i) -= d;
    }
    m(i, i) -= k;
  }
  Eigen::MatrixXd aug = Eigen::MatrixXd::Zero(n + 1, n + 1);
  aug.topLeftCorner(n, n) = m;
  for (Eigen::Index i = 0; i < n; ++i) aug(i, n) = b[i];
  const Eigen::MatrixXd e_aug = (aug * t).exp();
  LinearExact out;
  out.p = e_aug.topLeftCorner(n, n);
  out.lambda = e_aug.topRightCorner(n, 1);
  Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(x0.data(), n);
  out.mean = out.p * x + out.lambda;
  out.var = out.lambda;
  for (Eigen::Index j = 0; j < n; ++j) {
    if (x(j) == 0) continue;
    out.var += x(j) * out.p.col(j).cwiseProduct(Eigen::VectorXd::Ones(n) - out.p.col(j));
  }
  return out;
}

}  // namespace sadr::ssa::testing
