// SPDX-License-Identifier: MIT
// Rate laws in the SSA (one well-mixed voxel) against the CME solved by FSP:
// the propensity a(X) = V v(X / V) of a Michaelis-Menten and a Hill law
// (common/rate_law.hpp), and an expression law that spells the built-in one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "sadr/ssa/nsm_solver.hpp"
#include "ssa_test_support.hpp"

namespace sadr::ssa {
namespace {

using testing::Moments;

Model one_voxel_model(Reaction rx, std::vector<Species> species) {
  Model m;
  m.species = std::move(species);
  m.reactions = {std::move(rx)};
  m.box = testing::make_box(1, 1.0, false);
  m.smoothing_length = 0.5;
  return m;
}

/// The single particle of volume V = m / rho (the box holds it at x = 0.5).
ParticleState voxel(double volume) {
  ParticleState p = testing::make_lattice(1, 1, 1.0);
  p.masses[0] = volume;
  return p;
}

/// S -> 0 with the given law; E (species 1) is a catalyst the law may read.
Reaction decay(rate_law::Definition law) {
  Reaction rx;
  rx.def.name = "decay";
  rx.reactants = {{0, 1}};
  rx.def.law = std::move(law);
  return rx;
}

rate_law::Definition michaelis(double kcat, double km) {
  rate_law::Definition d;
  d.type = rate_law::Type::kMichaelisMenten;
  d.kcat = kcat;
  d.km = km;
  d.substrate = std::string("S");
  d.catalyst = std::string("E");
  return d;
}

rate_law::Definition hill(double vmax, double k, double n) {
  rate_law::Definition d;
  d.type = rate_law::Type::kHill;
  d.vmax = vmax;
  d.half = k;
  d.n = n;
  d.of = std::string("S");
  return d;
}

/// FSP of the pure death chain X -> X - 1 with rates a[x] (x = 0..x0), by
/// uniformization: P(t) = sum_k Poisson(k; L t) (I + Q/L)^k P(0) (exact up
/// to the 1e-15 Poisson tail; the chain is finite, no truncation error).
std::vector<double> death_chain(const std::vector<double>& a, double t) {
  const std::size_t n = a.size();
  const double lam = *std::max_element(a.begin(), a.end());
  std::vector<double> p(n, 0.0), out(n, 0.0), next(n);
  p[n - 1] = 1.0;
  double w = std::exp(-lam * t), cum = 0;
  for (int k = 0; cum < 1 - 1e-15 && k < 100000; ++k) {
    if (k > 0) w *= lam * t / k;
    cum += w;
    for (std::size_t x = 0; x < n; ++x) out[x] += w * p[x];
    for (std::size_t x = 0; x < n; ++x) {
      next[x] = p[x] * (1 - a[x] / lam) + (x + 1 < n ? p[x + 1] * a[x + 1] / lam : 0.0);
    }
    p.swap(next);
  }
  return out;
}

struct Exact {
  double mean = 0, var = 0, mu4 = 0;
};
Exact moments(const std::vector<double>& p) {
  Exact e;
  for (std::size_t x = 0; x < p.size(); ++x) e.mean += x * p[x];
  for (std::size_t x = 0; x < p.size(); ++x) {
    const double d = x - e.mean;
    e.var += d * d * p[x];
    e.mu4 += d * d * d * d * p[x];
  }
  return e;
}

// Michaelis-Menten (kcat = 0.8, Km = 5, E = 3 molecules held) and Hill (Vmax = 6,
// K = 8, n = 2.5) decay of S from 40 molecules in V = 1, at 4 times each: mean and
// variance z-tests, M = 2 laws x 4 times x 2 = 16 comparisons, family-wise
// false-failure rate 1e-4 (Bonferroni), R = 3000 realizations each.
TEST(RateLawCme, MichaelisMentenAndHillMatchFsp) {
  const std::vector<double> times = {1, 3, 6, 12};
  const int r_count = 3000;
  const std::int64_t s0 = 40, e0 = 3;
  const double zs = testing::z_star(1e-4, 16);
  double worst = 0;
  for (int which = 0; which < 2; ++which) {
    const rate_law::Definition law = which == 0 ? michaelis(0.8, 5) : hill(6, 8, 2.5);
    const rate_law::RateLaw f(law, {"S", "E"});
    std::vector<double> a(s0 + 1);
    for (std::int64_t x = 0; x <= s0; ++x) {  // V = 1: a(x) = v(x)
      const double c[2] = {static_cast<double>(x), static_cast<double>(e0)};
      a[x] = f.density(c, 0);
    }
    std::vector<Moments> mom(times.size());
    for (int r = 0; r < r_count; ++r) {
      NsmSolver s(one_voxel_model(decay(law), {{"S", 0}, {"E", 0}}),
                  rng::mix_seed(99, static_cast<std::uint64_t>(r) + 100003 * which));
      s.update_graph(voxel(1.0));
      s.set_counts(0, std::vector<std::int64_t>{s0});
      s.set_counts(1, std::vector<std::int64_t>{e0});
      for (std::size_t t = 0; t < times.size(); ++t) {
        s.advance(times[t]);
        mom[t].add(static_cast<double>(s.counts(0)[0]));
      }
      ASSERT_EQ(s.counts(1)[0], e0);  // the catalyst is never consumed
    }
    for (std::size_t t = 0; t < times.size(); ++t) {
      const Exact ex = moments(death_chain(a, times[t]));
      const double z_mean = (mom[t].mean() - ex.mean) / std::sqrt(ex.var / r_count);
      const double z_var = testing::variance_z(mom[t].var(), ex.var, ex.mu4, r_count);
      EXPECT_LE(std::abs(z_mean), zs) << "law " << which << " t=" << times[t];
      EXPECT_LE(std::abs(z_var), zs) << "law " << which << " t=" << times[t];
      worst = std::max({worst, std::abs(z_mean), std::abs(z_var)});
    }
  }
  RecordProperty("max_abs_z", std::to_string(worst));
}

// An expression that spells the built-in law gives the same propensities, hence
// the same trajectory from the same seed (bit for bit), in a voxel of V != 1.
TEST(RateLawCme, ExpressionSpellingABuiltInLawGivesIdenticalTrajectories) {
  rate_law::Definition e;
  e.type = rate_law::Type::kExpression;
  e.expression = std::string("kcat*E*S/(Km+S)");
  e.parameters = {{"kcat", 0.8}, {"Km", 5.0}};
  rate_law::Definition h;
  h.type = rate_law::Type::kExpression;
  h.expression = std::string("Vmax*S^n/(K^n+S^n)");
  h.parameters = {{"Vmax", 6.0}, {"K", 8.0}, {"n", 2.5}};
  for (const auto& [builtin, spelled] :
       {std::pair{michaelis(0.8, 5), e}, std::pair{hill(6, 8, 2.5), h}}) {
    std::vector<std::int64_t> trace[2];
    int k = 0;
    for (const auto& law : {builtin, spelled}) {
      NsmSolver s(one_voxel_model(decay(law), {{"S", 0}, {"E", 0}}), 4242);
      s.update_graph(voxel(2.0));
      s.set_counts(0, std::vector<std::int64_t>{400});
      s.set_counts(1, std::vector<std::int64_t>{7});
      for (double t = 0.5; t <= 20; t += 0.5) {
        s.advance(t);
        trace[k].push_back(s.counts(0)[0]);
      }
      ++k;
    }
    EXPECT_EQ(trace[0], trace[1]);
    EXPECT_LT(trace[0].back(), 400);
  }
}

// Propensities that become non-finite at run time are refused, with the reaction,
// the law and the counts (an expression admissible on the load grid, 1/(S - 3)).
TEST(RateLawCme, NonFinitePropensityIsRefused) {
  rate_law::Definition d;
  d.type = rate_law::Type::kExpression;
  d.expression = std::string("1/abs(S-3.5)");
  NsmSolver s(one_voxel_model(decay(d), {{"S", 0}, {"E", 0}}), 1);
  s.update_graph(voxel(2.0));  // V = 2: S = 7 gives C = 3.5
  try {
    s.set_counts(0, std::vector<std::int64_t>{7});
    FAIL() << "no error";
  } catch (const NumericalFailure& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("decay"), std::string::npos) << msg;
    EXPECT_NE(msg.find("1/abs(S-3.5)"), std::string::npos) << msg;
    EXPECT_NE(msg.find("S = 7"), std::string::npos) << msg;
  }
}

// The dependency graph: an event recomputes only the rate laws that read a species
// it changed. On a diffusing 4 x 4 lattice with two laws reading different species
// (and a mass-action reaction between them), after every stretch of events the
// cached propensity of every law in every voxel equals the one computed from the
// counts, and the trajectory is what it is with the cache (NSM vs the same model).
TEST(RateLawCme, CachedLawPropensitiesStayEqualToRecomputedOnes) {
  Model m;
  m.species = {{"S", 0.3}, {"E", 0.1}, {"P", 0.2}};
  m.box = testing::make_box(2, 4.0, true);
  m.smoothing_length = 1.5;
  Reaction mm = decay(michaelis(0.8, 5));
  mm.products = {{2, 1}};
  Reaction h = decay(hill(2, 3, 2));
  h.def.name = "hill";
  h.reactants = {{2, 1}};
  h.def.law->of = std::string("P");
  h.products = {{0, 1}};
  Reaction bind{"bind", {{1, 1}, {2, 1}}, {{1, 1}}, 0.05, {}, {}};
  m.reactions = {mm, h, bind};
  NsmSolver s(m, 77);
  s.update_graph(testing::make_lattice(2, 4, 1.0));
  std::vector<std::int64_t> x0(16), e0(16);
  for (std::size_t i = 0; i < 16; ++i) x0[i] = 5 + 3 * i, e0[i] = i % 3;
  s.set_counts(0, x0);
  s.set_counts(1, e0);
  const RdmeState& st = s.state();
  const ReactionTable& t = st.reactions();
  std::size_t checked = 0;
  for (double time = 0.05; time <= 6.0; time += 0.05) {
    s.advance(time);
    for (std::uint32_t i = 0; i < 16; ++i) {
      for (std::size_t r = 0; r < 2; ++r) {
        EXPECT_EQ(st.reaction_propensity(r, i), t.propensity(r, i, st.all_counts().data(), 16))
            << "reaction " << r << " voxel " << i << " t = " << time;
        ++checked;
      }
    }
  }
  EXPECT_GT(s.events(), 1000u);
  RecordProperty("checked", std::to_string(checked));
}

// Boundary fluxes (Reaction::def.boundary_areas, scene `boundary_fluxes`): the propensity is A_i
// j(X_i / V_i).

rate_law::Definition constant_flux(double q) {
  rate_law::Definition d;
  d.type = rate_law::Type::kExpression;
  d.expression = std::to_string(q);
  return d;
}

// A constant influx j = q into three boundary voxels of areas 0.5, 1, 1.5 (V = 1, no
// diffusion) gives Poisson counts of mean A_i q t in each and nothing elsewhere: mean and
// variance z-tests, 3 voxels x 2 times x 2 = 12 comparisons, family-wise false-failure rate
// 1e-4 (Bonferroni), R = 2000 realizations.
TEST(BoundaryFluxCme, ConstantInfluxGivesPoissonCountsOfMeanAqt) {
  Model m;
  m.species = {{"X", 0}};
  m.box = testing::make_box(1, 6.0, false);
  m.smoothing_length = 1.5;
  Reaction rx;
  rx.def.name = "influx";
  rx.products = {{0, 1}};
  rx.def.law = constant_flux(4.0);
  rx.voxels = {1, 2, 4};
  rx.def.boundary_areas = {0.5, 1.0, 1.5};
  m.reactions = {rx};
  const std::vector<double> times = {0.5, 2.0};
  const int r_count = 2000;
  const double zs = testing::z_star(1e-4, 12);
  std::vector<Moments> mom(times.size() * 3);
  for (int r = 0; r < r_count; ++r) {
    NsmSolver s(m, rng::mix_seed(17, static_cast<std::uint64_t>(r)));
    s.update_graph(testing::make_lattice(1, 6, 1.0));
    for (std::size_t t = 0; t < times.size(); ++t) {
      s.advance(times[t]);
      const auto x = s.counts(0);
      for (std::size_t k = 0; k < 3; ++k) mom[t * 3 + k].add(static_cast<double>(x[rx.voxels[k]]));
      ASSERT_EQ(x[0] + x[3] + x[5], 0);  // no flux outside the boundary voxels
    }
  }
  double worst = 0;
  for (std::size_t t = 0; t < times.size(); ++t) {
    for (std::size_t k = 0; k < 3; ++k) {
      const double mean =
          rx.def.boundary_areas[k] * 4.0 * times[t];  // Poisson: var = mean, mu4 = m + 3 m^2
      const Moments& mo = mom[t * 3 + k];
      const double z_mean = (mo.mean() - mean) / std::sqrt(mean / r_count);
      const double z_var = testing::variance_z(mo.var(), mean, mean + 3 * mean * mean, r_count);
      EXPECT_LE(std::abs(z_mean), zs) << "voxel " << k << " t=" << times[t];
      EXPECT_LE(std::abs(z_var), zs) << "voxel " << k << " t=" << times[t];
      worst = std::max({worst, std::abs(z_mean), std::abs(z_var)});
    }
  }
  RecordProperty("max_abs_z", std::to_string(worst));
}

// A Michaelis-Menten outflux S -> 0 through a boundary of area A = 0.5 on one voxel of V = 2
// (kcat = 0.8, Km = 5, E = 3 molecules): a(x) = A kcat (E/V) (x/V) / (Km + x/V), against the CME
// (FSP of the death chain); mean and variance z-tests at 4 times, 8 comparisons, family-wise
// false-failure rate 1e-4, R = 3000.
TEST(BoundaryFluxCme, MichaelisMentenOutfluxMatchesFsp) {
  const double area = 0.5, volume = 2.0;
  const std::vector<double> times = {1, 4, 10, 25};
  const int r_count = 3000;
  const std::int64_t s0 = 30, e0 = 3;
  Reaction rx = decay(michaelis(0.8, 5));
  rx.voxels = {0};
  rx.def.boundary_areas = {area};
  const rate_law::RateLaw f(*rx.def.law, {"S", "E"});
  std::vector<double> a(s0 + 1);
  for (std::int64_t x = 0; x <= s0; ++x) {
    const double c[2] = {static_cast<double>(x) / volume, static_cast<double>(e0) / volume};
    a[x] = area * f.density(c, 0);
  }
  const double zs = testing::z_star(1e-4, 8);
  std::vector<Moments> mom(times.size());
  for (int r = 0; r < r_count; ++r) {
    NsmSolver s(one_voxel_model(rx, {{"S", 0}, {"E", 0}}),
                rng::mix_seed(23, static_cast<std::uint64_t>(r)));
    s.update_graph(voxel(volume));
    s.set_counts(0, std::vector<std::int64_t>{s0});
    s.set_counts(1, std::vector<std::int64_t>{e0});
    for (std::size_t t = 0; t < times.size(); ++t) {
      s.advance(times[t]);
      mom[t].add(static_cast<double>(s.counts(0)[0]));
    }
  }
  double worst = 0;
  for (std::size_t t = 0; t < times.size(); ++t) {
    const Exact ex = moments(death_chain(a, times[t]));
    const double z_mean = (mom[t].mean() - ex.mean) / std::sqrt(ex.var / r_count);
    const double z_var = testing::variance_z(mom[t].var(), ex.var, ex.mu4, r_count);
    EXPECT_LE(std::abs(z_mean), zs) << "t=" << times[t];
    EXPECT_LE(std::abs(z_var), zs) << "t=" << times[t];
    worst = std::max({worst, std::abs(z_mean), std::abs(z_var)});
  }
  EXPECT_LT(mom.back().mean(), 0.8 * s0);  // the outflux has acted
  RecordProperty("max_abs_z", std::to_string(worst));
}

// The dependency graph with a boundary flux: an outflux law reading a diffusing species S on
// the 4 boundary voxels of a 4 x 4 lattice; after every stretch of events the cached
// propensity equals the one recomputed from the counts (A_i j(X_i / V_i)).
TEST(BoundaryFluxCme, CachedBoundaryPropensitiesStayEqualToRecomputedOnes) {
  Model m;
  m.species = {{"S", 0.3}, {"E", 0.1}};
  m.box = testing::make_box(2, 4.0, true);
  m.smoothing_length = 1.5;
  Reaction out = decay(michaelis(0.8, 5));
  out.def.name = "uptake";
  out.voxels = {0, 1, 2, 3};
  out.def.boundary_areas = {0.25, 0.5, 1.0, 2.0};
  Reaction in;
  in.def.name = "supply";
  in.products = {{0, 1}};
  in.def.rate = 2.0;
  m.reactions = {out, in};
  NsmSolver s(m, 78);
  s.update_graph(testing::make_lattice(2, 4, 1.0));
  std::vector<std::int64_t> x0(16), e0(16);
  for (std::size_t i = 0; i < 16; ++i) x0[i] = 5 + 3 * i, e0[i] = 1 + i % 3;
  s.set_counts(0, x0);
  s.set_counts(1, e0);
  const RdmeState& st = s.state();
  const ReactionTable& t = st.reactions();
  const rate_law::RateLaw f(*out.def.law, {"S", "E"});
  std::size_t checked = 0;
  for (double time = 0.05; time <= 6.0; time += 0.05) {
    s.advance(time);
    const auto x = s.counts(0), e = s.counts(1);
    for (std::uint32_t i = 0; i < 16; ++i) {
      const double cached = st.reaction_propensity(0, i);
      EXPECT_EQ(cached, t.propensity(0, i, st.all_counts().data(), 16)) << i << " t=" << time;
      const double c[2] = {x[i] / 1.0, e[i] / 1.0};  // V = 1
      EXPECT_EQ(cached, i < 4 && x[i] > 0 ? out.def.boundary_areas[i] * f.density(c, 0) : 0.0) << i;
      ++checked;
    }
  }
  EXPECT_GT(s.events(), 1000u);
  RecordProperty("checked", std::to_string(checked));
}

}  // namespace
}  // namespace sadr::ssa
