// SPDX-License-Identifier: MIT
// Moving walls (a prescribed wall velocity, positions fixed) with the SDPD backend, k_B T = 0:
//  - plane Couette start-up (bottom wall at rest, top wall sliding at U) against the series
//    u(y, t) = U y/H - (2U/pi) sum_n ((-1)^(n+1)/n) sin(n pi y/H) exp(-nu n^2 pi^2 t/H^2), for
//    each wall model;
//  - steady Taylor-Couette flow between an inner cylinder spinning at Omega and a fixed outer one
//    (2D annulus), u_theta(r) = A r + B/r, for each wall model;
//  - the wall velocity through save/restore (bit-identical continuation) and in the state read.
// Thresholds: the measured errors x 1.3 (bench/results/moving_walls.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "fluid_test_scenes.hpp"
#include "reference_solutions.hpp"
#include "sdpd/sdpd_backend.hpp"
#include "taylor_couette_scene.hpp"

namespace sadr::fluid::test {
namespace {

constexpr double kPi = std::numbers::pi;

// ---- plane Couette start-up -------------------------------------------------------------------

constexpr double kH = 1e-3, kNu = 1e-6, kRho = 1000.0, kU = 0.025;

double couette_exact(double y, double t) {
  double u = kU * y / kH;
  for (int n = 1; n < 4000; ++n) {
    const double e = std::exp(-kNu * n * n * kPi * kPi * t / (kH * kH));
    if (e < 1e-300) break;
    u -= 2 * kU / kPi * ((n % 2 == 1) ? 1.0 : -1.0) / n * std::sin(n * kPi * y / kH) * e;
  }
  return u;
}

FluidModel couette_model(WallModel wall_model, double dx) {
  FluidModel m;
  m.smoothing_length = 3.0 * dx;
  m.reference_density = kRho;
  m.sound_speed = 40.0 * kU;
  m.shear_viscosity = kRho * kNu;
  m.wall_model = wall_model;
  m.wall_regions = {{"bottom", {}, {-1, -1, -1}, {1, 0, 1}, {0, 1, 0}, {0, 0, 0}},
                    {"top", {}, {-1, kH, -1}, {1, 1, 1}, {0, -1, 0}, {0, kH, 0}}};
  return m;
}

/// ny fluid rows of spacing H/ny, 8 columns (periodic x), 4 wall layers per side, h = 3 dx; the
/// wall layers above y = H slide at U along x.
ParticleState couette_particles(int ny, FluidModel& m) {
  LatticeSpec ls;
  ls.dimension = 2;
  ls.n = {8, ny, 1};
  ls.dx = kH / ny;
  ls.periodic = {true, false, false};
  ls.wall_layers = 4;
  ls.rho0 = kRho;
  ParticleState p = make_lattice(ls, m.box);
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kind(i) == ParticleKind::kWall && p.positions[3 * i + 1] > kH) p.velocities[3 * i] = kU;
  }
  return p;
}

/// Scaled L2 and Linf errors (by U) of the fluid's u_x at the times `ts`.
std::vector<std::pair<double, double>> run_couette(int ny, WallModel wall_model,
                                                   const std::vector<double>& ts) {
  FluidModel m = couette_model(wall_model, kH / ny);
  const ParticleState p = couette_particles(ny, m);
  SdpdBackend b;
  b.initialize(m, p, {});
  std::vector<std::pair<double, double>> out;
  double t_prev = 0;
  std::uint64_t step = 0;
  for (const double t : ts) {
    b.advance(step++, t - t_prev);
    t_prev = t;
    ParticleState s;
    b.read_state(s);
    std::vector<double> u, ref, w;
    for (std::size_t i = 0; i < s.size(); ++i) {
      if (s.kind(i) == ParticleKind::kWall) continue;
      u.push_back(s.velocities[3 * i]);
      ref.push_back(couette_exact(s.positions[3 * i + 1], b.time()));
      w.push_back(s.masses[i] / s.densities[i]);
    }
    out.push_back(scaled_norms(u, ref, w, kU));
  }
  return out;
}

struct CouetteCase {
  WallModel wall;
  double l2_max;    ///< at the last time (steady), scaled by U
  double linf_max;  ///< at every time
};

class MovingWallCouette : public ::testing::TestWithParam<CouetteCase> {};

TEST_P(MovingWallCouette, StartupFollowsTheSeries) {
  const std::vector<double> ts{0.05, 0.1, 0.2, 0.5};  // t nu / H^2
  const auto errors = run_couette(20, GetParam().wall, ts);
  for (std::size_t k = 0; k < ts.size(); ++k) {
    std::printf("RESULT case=couette wall=%s H/dx=20 t=%g scaled_L2=%.3e scaled_Linf=%.3e\n",
                wall_model_name(GetParam().wall), ts[k], errors[k].first, errors[k].second);
    EXPECT_LT(errors[k].second, GetParam().linf_max) << "t " << ts[k];
  }
  EXPECT_LT(errors.back().first, GetParam().l2_max);
}

INSTANTIATE_TEST_SUITE_P(Walls, MovingWallCouette,
                         // measured (H/dx = 20): L2 at t = 0.5 1.73e-2, 6.26e-3, 1.85e-3; Linf at
                         // any time 8.14e-2, 3.16e-2, 6.11e-3
                         ::testing::Values(CouetteCase{WallModel::kStationary, 0.0225, 0.106},
                                           CouetteCase{WallModel::kMorrisExtrapolated, 0.0082,
                                                       0.041},
                                           CouetteCase{WallModel::kAdami, 0.0024, 0.0080}),
                         [](const ::testing::TestParamInfo<CouetteCase>& param_info) {
                           return std::string(wall_model_name(param_info.param.wall));
                         });

// ---- Taylor-Couette ---------------------------------------------------------------------------

struct TcCase {
  WallModel wall;
  double l2_max;  ///< scaled by Omega R1
};

class MovingWallTaylorCouette : public ::testing::TestWithParam<TcCase> {};

TEST_P(MovingWallTaylorCouette, SteadyProfileBetweenCylinders) {
  FluidModel m;
  m.smoothing_length = 3.0 * kDxTc;
  m.reference_density = 1.0;
  m.sound_speed = 10.0 * kOmega * kR1;
  m.shear_viscosity = kNuTc;
  m.wall_model = GetParam().wall;
  const ParticleState p = taylor_couette_particles(m);
  if (m.wall_model != WallModel::kMorrisExtrapolated) m.wall_tangents = {};
  SdpdBackend b;
  b.initialize(m, p, {});
  b.advance(0, 1.0);  // 8 decay times (R2 - R1)^2 / (pi^2 nu) of the slowest mode
  ParticleState s;
  b.read_state(s);
  std::vector<double> u, ref, w;
  double ur_max = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s.kind(i) == ParticleKind::kWall) continue;
    const double x = s.positions[3 * i], y = s.positions[3 * i + 1], r = std::hypot(x, y);
    const double vx = s.velocities[3 * i], vy = s.velocities[3 * i + 1];
    u.push_back((x * vy - y * vx) / r);
    ur_max = std::max(ur_max, std::fabs((x * vx + y * vy) / r));
    ref.push_back(taylor_couette_exact(r));
    w.push_back(s.masses[i] / s.densities[i]);
  }
  const auto [l2, linf] = scaled_norms(u, ref, w, kOmega * kR1);
  std::printf(
      "RESULT case=taylor_couette wall=%s gap/dx=10 scaled_L2=%.3e scaled_Linf=%.3e "
      "max_ur=%.3e\n",
      wall_model_name(GetParam().wall), l2, linf, ur_max / (kOmega * kR1));
  EXPECT_LT(l2, GetParam().l2_max);
}

INSTANTIATE_TEST_SUITE_P(Walls, MovingWallTaylorCouette,
                         // measured (gap/dx = 10): L2 5.21e-2, 3.73e-2, 2.38e-2
                         ::testing::Values(TcCase{WallModel::kStationary, 0.068},
                                           TcCase{WallModel::kMorrisExtrapolated, 0.049},
                                           TcCase{WallModel::kAdami, 0.031}),
                         [](const ::testing::TestParamInfo<TcCase>& param_info) {
                           return std::string(wall_model_name(param_info.param.wall));
                         });

// ---- the wall velocity in the state and through restarts --------------------------------------

TEST(MovingWalls, WallVelocityIsHeldReportedAndRestoredBitIdentically) {
  for (const WallModel wall :
       {WallModel::kStationary, WallModel::kMorrisExtrapolated, WallModel::kAdami}) {
    FluidModel m = couette_model(wall, kH / 10);
    const ParticleState p = couette_particles(10, m);
    SdpdBackend a;
    a.initialize(m, p, {});
    a.advance(0, 0.01);
    const std::string blob = a.save();
    a.advance(1, 0.01);
    ParticleState sa;
    a.read_state(sa);
    // a backend initialised with the walls at rest continues from the blob as the first did
    ParticleState at_rest = p;
    for (std::size_t i = 0; i < at_rest.size(); ++i) {
      if (at_rest.kind(i) == ParticleKind::kWall) at_rest.velocities[3 * i] = 0.0;
    }
    SdpdBackend b;
    b.initialize(m, at_rest, {});
    b.restore(blob);
    b.advance(1, 0.01);
    ParticleState sb;
    b.read_state(sb);
    EXPECT_EQ(sa.positions, sb.positions) << wall_model_name(wall);
    EXPECT_EQ(sa.velocities, sb.velocities) << wall_model_name(wall);
    for (std::size_t i = 0; i < sa.size(); ++i) {
      if (sa.kind(i) != ParticleKind::kWall) continue;
      const double want = p.positions[3 * i + 1] > kH ? kU : 0.0;
      ASSERT_EQ(sa.velocities[3 * i], want) << i;  // the prescribed velocity, held
      ASSERT_EQ(sa.velocities[3 * i + 1], 0.0) << i;
      ASSERT_EQ(sa.positions[3 * i], p.positions[3 * i]) << i;  // walls keep their positions
    }
  }
}

}  // namespace
}  // namespace sadr::fluid::test
