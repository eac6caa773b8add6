// SPDX-License-Identifier: MIT
// NSM and the direct-method baseline sample the same process: two-sample tests.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <vector>

#include "sadr/ssa/direct_solver.hpp"
#include "sadr/ssa/nsm_solver.hpp"
#include "ssa_test_support.hpp"

namespace sadr::ssa {
namespace {

Model small_model() {
  Model m = testing::diffusion_model(testing::make_box(1, 4.0, false), 1.5, 0.0);
  const double unit = 1.0 / (2.0 * lucy_f(1.0, 1.5, 1) / (1.0 + 0.01 * 2.25));  // hop rate 1
  m.species = {{"A", 0.5 * unit}, {"B", 0.5 * unit}, {"C", 0.2 * unit}};
  m.reactions = {{"bind", {{0, 1}, {1, 1}}, {{2, 1}}, 0.2, {}, {}},
                 {"unbind", {{2, 1}}, {{0, 1}, {1, 1}}, 0.5, {}, {}}};
  return m;
}

template <typename Solver>
void run(Solver& s, const std::vector<double>& times, std::vector<std::vector<double>>& out) {
  s.update_graph(testing::make_lattice(1, 4, 1.0));
  s.set_counts(0, std::vector<std::int64_t>{15, 0, 0, 0});
  s.set_counts(1, std::vector<std::int64_t>{0, 0, 0, 15});
  for (std::size_t t = 0; t < times.size(); ++t) {
    s.advance(times[t]);
    for (int sp = 0; sp < 3; ++sp) {
      for (int i = 0; i < 4; ++i) out[t * 12 + sp * 4 + i].push_back(s.counts(sp)[i]);
    }
  }
}

// 4 voxels x 3 species x 2 times = 24 Welch z tests of equal means, plus a chi-square
// homogeneity test of the total C count at t = 3 (p >= 1e-4). alpha_fw = 1e-4 for the
// z family (normal approximation, R = 3000 per solver); overall false-failure <= 2e-4.
TEST(NsmVsDirect, SameDistributionOnSmallCase) {
  const std::vector<double> times = {1.0, 3.0};
  const int r_count = 3000;
  std::vector<std::vector<double>> a(24), b(24);
  std::map<std::int64_t, std::array<int, 2>> c_total;
  for (int r = 0; r < r_count; ++r) {
    NsmSolver n(small_model(), rng::mix_seed(1, static_cast<std::uint64_t>(r)));
    DirectSolver d(small_model(), rng::mix_seed(2, static_cast<std::uint64_t>(r)));
    run(n, times, a);
    run(d, times, b);
    std::int64_t cn = 0, cd = 0;
    for (int i = 0; i < 4; ++i) cn += n.counts(2)[i], cd += d.counts(2)[i];
    ++c_total[cn][0];
    ++c_total[cd][1];
  }
  const double zs = testing::z_star(1e-4, 24);
  for (int k = 0; k < 24; ++k) {
    testing::Moments ma, mb;
    for (double x : a[k]) ma.add(x);
    for (double x : b[k]) mb.add(x);
    const double se = std::sqrt(ma.var() / r_count + mb.var() / r_count);
    if (se == 0) continue;
    EXPECT_LE(std::abs(ma.mean() - mb.mean()) / se, zs) << "point " << k;
  }
  // Chi-square homogeneity (2 x K table), cells pooled to >= 10 per column pair
  // (expected >= 5 per cell); a thin remainder joins the last cell.
  std::vector<std::array<double, 2>> table;
  std::array<double, 2> acc{0, 0};
  for (const auto& [c, cnt] : c_total) {
    acc[0] += cnt[0], acc[1] += cnt[1];
    if (acc[0] + acc[1] >= 10) table.push_back(acc), acc = {0, 0};
  }
  table.back()[0] += acc[0], table.back()[1] += acc[1];
  double stat = 0;
  for (const auto& cell : table) {
    const double e = (cell[0] + cell[1]) / 2;  // equal sample sizes
    for (int j = 0; j < 2; ++j) stat += (cell[j] - e) * (cell[j] - e) / e;
  }
  const int cells = static_cast<int>(table.size());
  ASSERT_GT(cells, 5);
  EXPECT_GE(testing::chi2_p(stat, cells - 1), 1e-4) << "chi2 " << stat << " cells " << cells;
}

}  // namespace
}  // namespace sadr::ssa
