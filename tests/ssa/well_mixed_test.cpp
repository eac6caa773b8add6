// SPDX-License-Identifier: MIT
// Well-mixed CME (one voxel, no diffusion) against exact references:
// birth-death closed form, stationary Poisson, dimerisation FSP (refs well_mixed_moments.csv).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "sadr/ssa/nsm_solver.hpp"
#include "ssa_test_support.hpp"

namespace sadr::ssa {
namespace {

using testing::Moments;

/// One particle with V = 1 in a walled 1D box: a single well-mixed voxel.
ParticleState one_voxel() {
  return testing::make_lattice(1, 1, 1.0);
}

Model single_voxel_model(std::vector<Species> species, std::vector<Reaction> reactions) {
  Model m;
  m.species = std::move(species);
  m.reactions = std::move(reactions);
  m.box = testing::make_box(1, 1.0, false);
  m.smoothing_length = 0.5;
  return m;
}

// Birth-death 0 -> A (b = 10 per unit volume and time, V = 1), A -> 0 (k = 0.1).
// Exact: X(t) = Bin(x0, e^-kt) + Poisson((b/k)(1 - e^-kt)).
// Comparison points: 2 initial states x 7 times, mean AND variance tests: M = 28.
// Family-wise false-failure rate alpha_fw = 1e-4 (Bonferroni), R = 4000 realizations.
TEST(WellMixed, BirthDeathMeanAndVarianceMatchClosedForm) {
  const double b = 10, k = 0.1;
  const std::vector<double> times = {0.5, 1, 2, 5, 10, 20, 50};
  const int r_count = 4000;
  const double zs = testing::z_star(1e-4, 28);
  double worst = 0;
  for (std::int64_t x0 : {std::int64_t{0}, std::int64_t{200}}) {
    std::vector<Moments> mom(times.size());
    for (int r = 0; r < r_count; ++r) {
      NsmSolver s(single_voxel_model({{"A", 0}}, {{"birth", {}, {{0, 1}}, b, {}, {}},
                                                  {"death", {{0, 1}}, {}, k, {}, {}}}),
                  rng::mix_seed(1234, static_cast<std::uint64_t>(r) + 7919 * x0));
      s.update_graph(one_voxel());
      const std::vector<std::int64_t> init = {x0};
      s.set_counts(0, init);
      for (std::size_t t = 0; t < times.size(); ++t) {
        s.advance(times[t]);
        mom[t].add(static_cast<double>(s.counts(0)[0]));
      }
    }
    for (std::size_t t = 0; t < times.size(); ++t) {
      const double p = std::exp(-k * times[t]);
      const double lam = (b / k) * (1 - p);
      const double mean = x0 * p + lam;
      const double var = x0 * p * (1 - p) + lam;
      // 4th central moment of a sum of independent variables: mu4 = mu4X + mu4Y + 6 s2X s2Y.
      const double vb = x0 * p * (1 - p);
      const double mu4 = testing::binomial_mu4(x0, p) + (lam + 3 * lam * lam) + 6 * vb * lam;
      const double z_mean = (mom[t].mean() - mean) / std::sqrt(var / r_count);
      const double z_var = testing::variance_z(mom[t].var(), var, mu4, r_count);
      EXPECT_LE(std::abs(z_mean), zs) << "x0=" << x0 << " t=" << times[t];
      EXPECT_LE(std::abs(z_var), zs) << "x0=" << x0 << " t=" << times[t];
      worst = std::max({worst, std::abs(z_mean), std::abs(z_var)});
    }
  }
  RecordProperty("max_abs_z", std::to_string(worst));
}

// Stationary law Poisson(100): start at x0 = 100, sample at t = 100 (within 5e-3 of
// stationary in every moment: X = Bin(100, e^-10) + Poisson(100 (1 - e^-10))).
// Chi-square goodness of fit on bins pooled to expected counts >= 5; PASS iff
// p >= 1e-4 (false-failure rate 1e-4). R = 4000.
TEST(WellMixed, BirthDeathStationaryLawIsPoisson) {
  const int r_count = 4000;
  std::vector<int> hist(400, 0);
  for (int r = 0; r < r_count; ++r) {
    NsmSolver s(single_voxel_model({{"A", 0}}, {{"birth", {}, {{0, 1}}, 10.0, {}, {}},
                                                {"death", {{0, 1}}, {}, 0.1, {}, {}}}),
                rng::mix_seed(99, static_cast<std::uint64_t>(r)));
    s.update_graph(one_voxel());
    const std::vector<std::int64_t> init = {100};
    s.set_counts(0, init);
    s.advance(100.0);
    ++hist[std::min<std::int64_t>(s.counts(0)[0], 399)];
  }
  // Poisson(100) pmf, pooled.
  std::vector<double> pmf(400);
  double total = 0;
  for (int x = 0; x < 400; ++x) {
    pmf[x] = std::exp(x * std::log(100.0) - 100.0 - std::lgamma(x + 1.0));
    total += pmf[x];
  }
  pmf[399] += 1 - total;
  // Pool left to right until the expected count reaches 5; merge a thin remainder.
  std::vector<double> e_bins, o_bins;
  double exp_acc = 0, obs_acc = 0;
  for (int x = 0; x < 400; ++x) {
    exp_acc += pmf[x] * r_count;
    obs_acc += hist[x];
    if (exp_acc >= 5) {
      e_bins.push_back(exp_acc), o_bins.push_back(obs_acc);
      exp_acc = obs_acc = 0;
    }
  }
  e_bins.back() += exp_acc, o_bins.back() += obs_acc;
  double stat = 0;
  for (std::size_t k = 0; k < e_bins.size(); ++k) {
    stat += (o_bins[k] - e_bins[k]) * (o_bins[k] - e_bins[k]) / e_bins[k];
  }
  const int bins = static_cast<int>(e_bins.size());
  ASSERT_GT(bins, 20);
  const double p = testing::chi2_p(stat, bins - 1);
  EXPECT_GE(p, 1e-4) << "chi2 = " << stat << " bins = " << bins;
}

// Dimerisation A + A -> B (propensity c X(X-1)/2, c = 0.01, V = 1 so k = c) and its
// reversible variant (B -> 2A, d = 0.1), x0 = 30: FSP-exact mean of A and B at 7 times.
// M = 2 models x 7 times x 2 species = 28 mean tests with the exact FSP variance;
// alpha_fw = 1e-4; R = 4000.
TEST(WellMixed, DimerisationMatchesFsp) {
  const auto rows = testing::read_csv(testing::refs_path("well_mixed_moments.csv"));
  const std::vector<double> times = {0.5, 1, 2, 5, 10, 20, 50};
  const int r_count = 4000;
  const double zs = testing::z_star(1e-4, 28);
  int compared = 0;
  for (double d : {0.0, 0.1}) {
    std::vector<Reaction> rx = {{"dimerise", {{0, 2}}, {{1, 1}}, 0.01, {}, {}}};
    if (d > 0) rx.push_back({"split", {{1, 1}}, {{0, 2}}, d, {}, {}});
    std::vector<Moments> ma(times.size()), mb(times.size());
    for (int r = 0; r < r_count; ++r) {
      NsmSolver s(single_voxel_model({{"A", 0}, {"B", 0}}, rx),
                  rng::mix_seed(5, static_cast<std::uint64_t>(r) + (d > 0 ? 100000 : 0)));
      s.update_graph(one_voxel());
      const std::vector<std::int64_t> init = {30};
      s.set_counts(0, init);
      for (std::size_t t = 0; t < times.size(); ++t) {
        s.advance(times[t]);
        ma[t].add(static_cast<double>(s.counts(0)[0]));
        mb[t].add(static_cast<double>(s.counts(1)[0]));
        ASSERT_EQ(s.counts(0)[0] + 2 * s.counts(1)[0], 30);  // conservation law
      }
    }
    const std::string params = d > 0 ? "N0=30,c=0.01,d=0.1" : "N0=30,c=0.01,d=0";
    for (const auto& row : rows) {
      if (row.at("model") != "dimerisation" || row.at("params") != params) continue;
      if (row.at("t") == "inf") continue;
      const double t = std::stod(row.at("t"));
      const auto it = std::find(times.begin(), times.end(), t);
      ASSERT_NE(it, times.end());
      const auto& m = row.at("species") == "A" ? ma[it - times.begin()] : mb[it - times.begin()];
      const double mean = std::stod(row.at("mean")), var = std::stod(row.at("var"));
      const double z = (m.mean() - mean) / std::sqrt(var / r_count);
      EXPECT_LE(std::abs(z), zs) << params << " t=" << t << " " << row.at("species") << " mean "
                                 << m.mean() << " vs " << mean;
      ++compared;
    }
  }
  EXPECT_EQ(compared, 28);
}

}  // namespace
}  // namespace sadr::ssa
