// SPDX-License-Identifier: MIT
// Unit/property: the static backend and the discrete species Laplacian on lattices.
#include <gtest/gtest.h>

#include <cmath>

#include "fluid_test_scenes.hpp"
#include "sadr/common/status.hpp"
#include "static/static_backend.hpp"

namespace sadr::fluid {
namespace {

// Looks up kappa_eff/kappa in refs/sph_consistency.csv.
double consistency_ratio(int dim, double eps, double h_over_dx) {
  const auto cols = test::read_csv(test::refs_dir() + "/sph_consistency.csv");
  for (std::size_t k = 0; k < cols.at("dim").size(); ++k) {
    if (cols.at("dim")[k] == dim && std::fabs(cols.at("eps")[k] - eps) < 1e-12 &&
        std::fabs(cols.at("h_over_dx")[k] - h_over_dx) < 1e-9) {
      return cols.at("kappa_eff_over_kappa")[k];
    }
  }
  throw std::runtime_error("ratio not in sph_consistency.csv");
}

struct LapCase {
  int dim;
  double h_over_dx;
  double eps;
};
class Laplacian : public ::testing::TestWithParam<LapCase> {};

// One trapezoidal step of dC/dt = L C on C = x^2: the interior rate is exactly 2 kappa ratio.
TEST_P(Laplacian, OfXSquaredIsTwoKappaRatio) {
  const auto c = GetParam();
  test::LatticeSpec ls;
  ls.dimension = c.dim;
  const int side = c.dim == 1 ? 41 : c.dim == 2 ? 21 : 13;
  ls.n = {side, c.dim > 1 ? side : 1, c.dim > 2 ? side : 1};
  ls.dx = 0.5;
  ls.periodic = {false, false, false};
  FluidModel m;
  ParticleState p = test::make_lattice(ls, m.box);
  m.smoothing_length = c.h_over_dx * ls.dx;
  m.diffusion_eps = c.eps;
  const double kappa = 0.2;
  m.species.push_back({"C", kappa, true, {}, {}});
  std::vector<double> c0(p.size());
  const double xc = 0.5 * side * ls.dx;
  std::size_t centre = 0;
  double best = 1e9;
  for (std::size_t i = 0; i < p.size(); ++i) {
    double r2 = 0;
    for (int a = 0; a < c.dim; ++a) r2 += std::pow(p.positions[3 * i + a] - xc, 2);
    if (r2 < best) {
      best = r2;
      centre = i;
    }
    c0[i] = std::pow(p.positions[3 * i] - 1.3, 2);
  }
  StaticBackend b;
  b.initialize(m, p, {c0});
  const double dt = 1e-3;
  const auto rep = b.advance(0, dt);
  EXPECT_EQ(rep.substeps, 1u);
  const double rate = (b.concentrations(0)[centre] - c0[centre]) / dt;
  const double expected = 2.0 * kappa * consistency_ratio(c.dim, c.eps, c.h_over_dx);
  EXPECT_NEAR(rate, expected, 1e-9 * expected) << "dim " << c.dim;
}

INSTANTIATE_TEST_SUITE_P(Lattices, Laplacian,
                         ::testing::Values(LapCase{1, 1.8, 0.01}, LapCase{1, 3.0, 0.01},
                                           LapCase{1, 3.0, 0.0}, LapCase{2, 3.0, 0.01},
                                           LapCase{2, 2.0, 0.0}, LapCase{3, 2.0, 0.01},
                                           LapCase{3, 1.8, 0.0}));

TEST(StaticBackend, ParticlesNeverMoveAndNoSpeciesCostsNothing) {
  test::LatticeSpec ls;
  ls.n = {6, 6, 1};
  FluidModel m;
  ParticleState p = test::make_lattice(ls, m.box);
  p.velocities.assign(p.velocities.size(), 3.0);
  m.smoothing_length = 2.0;
  StaticBackend b;
  b.initialize(m, p, {});
  const auto rep = b.advance(0, 10.0);
  EXPECT_EQ(rep.substeps, 0u);
  EXPECT_FALSE(rep.particles_moved);
  EXPECT_DOUBLE_EQ(b.time(), 10.0);
  ParticleState out;
  b.read_state(out);
  EXPECT_EQ(out.positions, p.positions);
  EXPECT_EQ(out.densities, p.densities);
  for (double v : out.velocities) EXPECT_EQ(v, 0.0);
}

TEST(StaticBackend, NoFluxWallsConserveAndDirichletHolds) {
  test::LatticeSpec ls;
  ls.dimension = 1;
  ls.n = {30, 1, 1};
  ls.periodic = {false, false, false};
  ls.wall_layers = 3;
  FluidModel m;
  ParticleState p = test::make_lattice(ls, m.box);
  m.smoothing_length = 2.5;
  m.species.push_back({"free", 0.3, true, {}, {}});
  SpeciesSpec held{"held", 0.3, true, {WallCondition::Type::kDirichlet, 2.0}, {}};
  m.species.push_back(held);
  std::vector<double> a(p.size(), 0.0), bb(p.size(), 0.0);
  for (std::size_t i = 0; i < p.size(); ++i) a[i] = p.positions[3 * i] < 10 ? 1.0 : 0.0;
  StaticBackend b;
  b.initialize(m, p, {a, bb});
  auto fluid_total = [&](int s) {
    double t = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.kind(i) == ParticleKind::kFluid) t += b.concentrations(s)[i];
    }
    return t;
  };
  const double t0 = fluid_total(0);
  b.advance(0, 2000.0);
  EXPECT_NEAR(fluid_total(0), t0, 1e-10 * t0);
  // Dirichlet walls at 2 fill the domain towards 2 (and walls stay exactly 2).
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kind(i) == ParticleKind::kWall) {
      EXPECT_EQ(b.concentrations(1)[i], 2.0);
    }
  }
  EXPECT_GT(b.concentrations(1)[3 + 15], 1.5);
  // save/restore
  const auto blob = b.save();
  b.advance(1, 5.0);
  const auto after = b.concentrations(1);
  b.restore(blob);
  b.advance(1, 5.0);
  EXPECT_EQ(b.concentrations(1), after);
}

// Wall regions given as explicit particle lists (the service's RegionMembership) behave like
// regions given by boxes.
TEST(StaticBackend, WallRegionByParticleListEqualsByBox) {
  test::LatticeSpec ls;
  ls.dimension = 1;
  ls.n = {20, 1, 1};
  ls.periodic = {false, false, false};
  ls.wall_layers = 2;
  FluidModel m;
  ParticleState p = test::make_lattice(ls, m.box);
  m.smoothing_length = 1.8;
  using T = WallCondition::Type;
  m.species.push_back({"C", 0.5, true, {}, {{T::kDirichlet, 1.0}}});
  FluidModel by_list = m;
  m.wall_regions = {{"left", {}, {-10, 0, 0}, {0, 0, 0}, {1, 0, 0}, {0, 0, 0}}};
  WallRegion listed{"left", {}, {}, {}, {1, 0, 0}, {0, 0, 0}};
  for (std::uint32_t i = 0; i < p.size(); ++i) {
    if (p.kind(i) == ParticleKind::kWall && p.positions[3 * i] < 0) listed.particles.push_back(i);
  }
  by_list.wall_regions = {listed};
  StaticBackend a, b;
  a.initialize(m, p, {});
  b.initialize(by_list, p, {});
  a.advance(0, 50.0);
  b.advance(0, 50.0);
  EXPECT_EQ(a.concentrations(0), b.concentrations(0));
  EXPECT_GT(a.concentrations(0)[2], 0.1);  // the left Dirichlet wall fed the line
  by_list.wall_regions[0].particles.push_back(999);
  EXPECT_THROW(b.initialize(by_list, p, {}), InvalidArgument);
}

TEST(StaticBackend, AplusBReactionConservesDifference) {
  test::LatticeSpec ls;
  ls.n = {6, 6, 1};
  FluidModel m;
  ParticleState p = test::make_lattice(ls, m.box);
  m.smoothing_length = 2.0;
  m.species.push_back({"A", 0.0, true, {}, {}});
  m.species.push_back({"B", 0.0, true, {}, {}});
  m.reactions.push_back({"ann", {{0, 1}, {1, 1}}, {}, 0.5, {}, {}});
  m.max_time_step = 0.01;
  StaticBackend b;
  b.initialize(m, p, {std::vector<double>(p.size(), 2.0), std::vector<double>(p.size(), 1.0)});
  const auto rep = b.advance(0, 1.0);
  EXPECT_EQ(rep.limiting_criterion, "reaction");
  // exact: a - b = 1, b(t) = 1/(2 e^{kt} - 1) with k (a-b) = 0.5
  const double bex = 1.0 / (2.0 * std::exp(0.5) - 1.0);
  EXPECT_NEAR(b.concentrations(1)[0], bex, 1e-5);  // Heun error O(dt^2) ~ 1e-6
  EXPECT_NEAR(b.concentrations(0)[0] - b.concentrations(1)[0], 1.0, 1e-12);
}

// The bound the service reports after init (InitReply, the plan's figure) has the reaction limit:
// a stiff decay sets it, and the first advance takes exactly ceil(T / dt) sub-steps (the limit of
// a first-order law does not depend on the concentrations). The orchestrator's former estimate
// (diffusion only) said 1 here.
TEST(StaticBackend, SubstepBoundNamesTheReactionLimit) {
  test::LatticeSpec ls;
  ls.n = {6, 6, 1};
  FluidModel m;
  ParticleState p = test::make_lattice(ls, m.box);
  m.smoothing_length = 2.0;
  m.species.push_back({"A", 1e-4, true, {}, {}});
  m.reactions.push_back({"decay", {{0, 1}}, {}, 40.0, {}, {}});
  StaticBackend b;
  b.initialize(m, p, {std::vector<double>(p.size(), 1.0)});
  const SubstepBound bound = b.current_substep_bound();
  EXPECT_EQ(bound.limit_name, "reaction");
  EXPECT_EQ(bound.criterion, "reaction");
  EXPECT_EQ(bound.dt, bound.limit);
  const double predicted = std::ceil(1.0 / bound.dt * (1.0 - 1e-12));
  EXPECT_GT(predicted, 10.0);
  const auto rep = b.advance(0, 1.0);
  EXPECT_EQ(rep.substeps, static_cast<std::uint32_t>(predicted));
  EXPECT_EQ(rep.limiting_criterion, "reaction");
  // max_time_step below the limit caps it and is named; force takes it as it is
  m.max_time_step = 0.5 * bound.limit;
  StaticBackend capped;
  capped.initialize(m, p, {std::vector<double>(p.size(), 1.0)});
  EXPECT_EQ(capped.current_substep_bound().criterion, "max_time_step");
  EXPECT_EQ(capped.current_substep_bound().dt, m.max_time_step);
}

// --- reaction sites (ReactionSpec::def.kinds / ::particles) and WallCondition::kFree -------------

// 1D chain of `n` fluid particles with `layers` wall layers at each end, one species.
FluidModel chain_model(ParticleState& p, int n, int layers, double kappa, WallCondition wall) {
  test::LatticeSpec ls;
  ls.dimension = 1;
  ls.n = {n, 1, 1};
  ls.periodic = {false, true, true};
  ls.wall_layers = layers;
  FluidModel m;
  p = test::make_lattice(ls, m.box);
  m.smoothing_length = 2.0;
  m.species.push_back({"A", kappa, true, wall, {}});
  return m;
}

TEST(ReactionSites, ProductionRestrictedToParticleListChangesOnlyThose) {
  ParticleState p;
  FluidModel m = chain_model(p, 12, 2, 0.0, {});
  m.reactions.push_back({"make", {}, {{0, 1}}, 2.0, {}, {4, 9}});
  StaticBackend b;
  b.initialize(m, p, {std::vector<double>(p.size(), 0.0)});
  b.advance(0, 0.5);
  const auto& c = b.concentrations(0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_DOUBLE_EQ(c[i], (i == 4 || i == 9) ? 1.0 : 0.0) << "particle " << i;
  }
}

TEST(ReactionSites, DefaultReactionsFireOnFluidOnlyKindsSelectWalls) {
  for (const bool on_walls : {false, true}) {
    ParticleState p;
    FluidModel m = chain_model(p, 10, 3, 0.0, {});
    ReactionSpec r{"make", {}, {{0, 1}}, 1.0, {}, {}};
    if (on_walls) r.def.kinds = {ParticleKind::kWall};
    m.reactions.push_back(r);
    StaticBackend b;
    b.initialize(m, p, {std::vector<double>(p.size(), 0.0)});
    b.advance(0, 1.0);
    const auto& c = b.concentrations(0);
    for (std::size_t i = 0; i < p.size(); ++i) {
      const bool wall = p.kind(i) == ParticleKind::kWall;
      EXPECT_DOUBLE_EQ(c[i], wall == on_walls ? 1.0 : 0.0) << "particle " << i;
    }
  }
}

TEST(ReactionSites, ParticleIndexOutOfRangeIsRejected) {
  ParticleState p;
  FluidModel m = chain_model(p, 8, 2, 0.1, {});
  m.reactions.push_back({"make", {}, {{0, 1}}, 1.0, {}, {3, 99}});
  StaticBackend b;
  try {
    b.initialize(m, p, {});
    FAIL() << "expected InvalidArgument";
  } catch (const InvalidArgument& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("reactions[0].particles[1] = 99"), std::string::npos) << msg;
  }
}

TEST(FreeWall, StaticChainConservesAndEquilibratesThroughTheWall) {
  // Species starts in the left wall layers only. kNoFlux keeps it there; kFree lets it diffuse
  // through the (immobile) wall particles into the fluid until uniform, conserving the total.
  for (const auto type : {WallCondition::Type::kNoFlux, WallCondition::Type::kFree}) {
    ParticleState p;
    FluidModel m = chain_model(p, 16, 3, 1.0, {type, 0.0});
    std::vector<double> c0(p.size(), 0.0);
    double total0 = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.positions[3 * i] < 0) c0[i] = 1.0;
      total0 += c0[i];
    }
    StaticBackend b;
    b.initialize(m, p, {c0});
    b.advance(0, 3000.0);
    const auto& c = b.concentrations(0);
    double total = 0, fluid_max = 0, dev = 0;
    const double mean = total0 / static_cast<double>(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) {
      total += c[i];
      if (p.kind(i) == ParticleKind::kFluid) fluid_max = std::max(fluid_max, std::fabs(c[i]));
      dev = std::max(dev, std::fabs(c[i] - mean));
    }
    EXPECT_NEAR(total, total0, 1e-11);
    if (type == WallCondition::Type::kNoFlux) {
      EXPECT_EQ(fluid_max, 0.0);
      EXPECT_EQ(c[0], 1.0);
    } else {
      EXPECT_LT(dev, 1e-6 * mean) << "mean " << mean;
    }
  }
}

}  // namespace
}  // namespace sadr::fluid
