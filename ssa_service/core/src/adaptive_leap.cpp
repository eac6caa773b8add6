// SPDX-License-Identifier: MIT
#include "sadr/ssa/adaptive_leap.hpp"

#include <algorithm>
#include <boost/random/binomial_distribution.hpp>
#include <boost/random/poisson_distribution.hpp>
#include <cmath>
#include <limits>

namespace sadr::ssa {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// The leap stream as a UniformRandomBitGenerator. The distributions below are Boost.Random's
/// (binomial: BTRD, Hormann 1993; exact in distribution, and the same on every standard
/// library): GCC 12's std::binomial_distribution is measurably biased for large n and small p
/// (n = 1e5, p = 1e-4: mean +0.26 %, 5 standard errors in 4e5 draws), which is the leap's
/// regime. They are made afresh for every draw, so a draw is a function of the stream state.
struct Bits {
  using result_type = std::uint64_t;
  static constexpr result_type min() { return 0; }
  static constexpr result_type max() { return std::numeric_limits<result_type>::max(); }
  result_type operator()() { return rng->next(); }
  rng::Xoshiro256* rng;
};

std::int64_t binomial(Bits& bits, std::int64_t n, double p) {
  if (n <= 0 || !(p > 0)) return 0;
  if (p >= 1) return n;
  return boost::random::binomial_distribution<std::int64_t, double>(n, p)(bits);
}

std::int64_t poisson(Bits& bits, double mean) {
  if (!(mean > 0)) return 0;
  return boost::random::poisson_distribution<std::int64_t, double>(mean)(bits);
}

/// Whether the pair can diffuse at all (open or reservoir, with a positive jump rate).
bool diffuses(const RdmeState& st, int s, std::uint32_t i) {
  return st.role(s, i) != RdmeState::VoxelRole::kClosed && st.jump_weight_sum(s, i) > 0;
}

}  // namespace

AdaptiveLeap::AdaptiveLeap(double tolerance, std::uint64_t seed)
    : eps_(tolerance),
      n_c_(std::max<std::int64_t>(10, static_cast<std::int64_t>(std::ceil(1.0 / tolerance)))),
      rng_(seed, kStreamId) {}

bool AdaptiveLeap::classify(const RdmeState& st) {
  const std::size_t n = st.voxel_count();
  mask_.assign(static_cast<std::size_t>(st.species_count()) * n, 0);
  bool any = false;
  for (int s : st.diffusing_species()) {
    const std::span<const std::int64_t> x = st.counts(s);
    std::uint8_t* m = mask_.data() + static_cast<std::size_t>(s) * n;
    for (std::size_t i = 0; i < n; ++i) {
      if (x[i] < n_c_) continue;
      const auto v = static_cast<std::uint32_t>(i);
      if (!diffuses(st, s, v)) continue;
      m[i] = 1;
      any = true;
    }
  }
  return any;
}

double AdaptiveLeap::window(const RdmeState& st) {
  const std::size_t n = st.voxel_count();
  const DiffusionGraph& g = st.graph();
  const ReactionTable& table = st.reactions();
  double tau = kInf;
  jump_rate_ = 0;
  for (int s : st.diffusing_species()) {
    const std::uint8_t* m = mask_.data() + static_cast<std::size_t>(s) * n;
    if (std::find(m, m + n, std::uint8_t{1}) == m + n) continue;
    const std::span<const std::int64_t> x = st.counts(s);
    const double kappa = st.kappa(s);
    // Expected arrivals of s in every voxel: scatter each row's outflow to its targets.
    flow_in_.assign(n, 0.0);
    for (std::size_t j = 0; j < n; ++j) {
      const auto v = static_cast<std::uint32_t>(j);
      if (x[j] == 0 || !diffuses(st, s, v)) continue;
      const double per = kappa * static_cast<double>(x[j]);
      for (std::uint32_t k = g.row_start[j]; k < st.edge_end(s, v); ++k) {
        if (st.has_free_walls(s) && !st.uses_edge(s, v, k)) continue;
        flow_in_[g.edges[k].target] += per * g.edges[k].weight;
      }
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (!m[i]) continue;
      const auto v = static_cast<std::uint32_t>(i);
      const double a = kappa * st.jump_weight_sum(s, v);  // per-molecule jump rate out of i
      tau = std::min(tau, eps_ / a);
      jump_rate_ += a * static_cast<double>(x[i]);
      if (st.fixed(s, v)) continue;  // a held count does not change
      const double xi = static_cast<double>(x[i]);
      double mu = flow_in_[i] - a * xi;
      double sigma2 = flow_in_[i] + a * xi;
      for (std::size_t r = 0; r < table.reaction_count(); ++r) {
        const double p = st.reaction_propensity(r, v);
        if (!(p > 0)) continue;
        for (const auto& [sp, delta] : table.reaction(r).change) {
          if (sp != s) continue;
          mu += delta * p;
          sigma2 += static_cast<double>(delta) * delta * p;
        }
      }
      const double bound = std::max(eps_ * xi, 1.0);
      if (mu != 0) tau = std::min(tau, bound / std::abs(mu));
      if (sigma2 > 0) tau = std::min(tau, bound * bound / sigma2);
    }
  }
  return tau;
}

std::uint64_t AdaptiveLeap::leap(RdmeState& st, double tau) {
  const std::size_t n = st.voxel_count();
  const DiffusionGraph& g = st.graph();
  Bits bits{&rng_};
  std::uint64_t moved = 0;
  for (int s : st.diffusing_species()) {
    const std::uint8_t* m = mask_.data() + static_cast<std::size_t>(s) * n;
    if (std::find(m, m + n, std::uint8_t{1}) == m + n) continue;
    const std::span<const std::int64_t> x = st.counts(s);
    start_.assign(x.begin(), x.end());  // every pair leaps from the window-start counts
    const double kappa = st.kappa(s);
    for (std::size_t i = 0; i < n; ++i) {
      if (!m[i]) continue;
      const auto v = static_cast<std::uint32_t>(i);
      const double w_sum = st.jump_weight_sum(s, v);
      const double a = kappa * w_sum;
      const bool held = st.fixed(s, v);
      // Open: each of the X molecules leaves with probability a tau (<= eps by window()):
      // the expected number of jumps out over tau, so the mean flux and the effective
      // diffusivity are exact to first order (1 - exp(-a tau), the chance of at least one
      // jump, would slow diffusion by a tau / 2). Held: the reservoir emits a Poisson process
      // of rate X a.
      const std::int64_t k_out = held ? poisson(bits, static_cast<double>(start_[i]) * a * tau)
                                      : binomial(bits, start_[i], a * tau);
      if (k_out == 0) continue;
      usable_.clear();
      for (std::uint32_t k = g.row_start[i]; k < st.edge_end(s, v); ++k) {
        if (st.has_free_walls(s) && !st.uses_edge(s, v, k)) continue;
        usable_.push_back(k);
      }
      if (!held) st.add_count(s, v, -k_out);
      std::int64_t rest = k_out;
      double w_rest = w_sum;
      for (std::size_t e = 0; e < usable_.size() && rest > 0; ++e) {
        const DiffusionGraph::Edge& edge = g.edges[usable_[e]];
        const std::int64_t k_j =
            e + 1 == usable_.size() ? rest : binomial(bits, rest, edge.weight / w_rest);
        rest -= k_j;
        w_rest -= edge.weight;
        if (k_j > 0 && !st.fixed(s, edge.target)) st.add_count(s, edge.target, k_j);
      }
      moved += static_cast<std::uint64_t>(k_out);
    }
  }
  moved_ += moved;
  return moved;
}

}  // namespace sadr::ssa
