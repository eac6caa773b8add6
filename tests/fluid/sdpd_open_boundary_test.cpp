// SPDX-License-Identifier: MIT
// Property: SDPD open boundary (inlet/outlet buffers, recycling; docs/fluid-core.md 2).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "open_channel_scene.hpp"
#include "sadr/common/status.hpp"
#include "sadr/fluid/parallel.hpp"
#include "sdpd/sdpd_backend.hpp"
#ifdef SADR_HAVE_OPENMP
#include <omp.h>
#endif

namespace sadr::fluid::test {
namespace {

// Isolated particles (rows 0.5 apart, h = 0.2: no pair forces): the transitions of one
// sub-step can be written down by hand.
struct HandMade {
  FluidModel model;
  ParticleState state;
};

HandMade hand_made() {
  HandMade s;
  FluidModel& m = s.model;
  m.box.dimension = 2;
  m.box.lo = {-0.5, 0, 0};
  m.box.hi = {1.5, 3.0, 1};
  m.box.periodic = {false, false, false};
  m.smoothing_length = 0.2;
  m.sound_speed = 10;
  m.shear_viscosity = 0.1;
  m.max_time_step = 0.1;
  m.force_time_step = true;  // one sub-step of 0.1
  auto& ob = m.open_boundary;
  ob.enabled = true;
  ob.inlet_lo = -0.5;
  ob.fluid_lo = 0;
  ob.fluid_hi = 1.0;
  ob.outlet_hi = 1.5;
  ob.mean_velocity = 1.0;
  ParticleState& p = s.state;
  p.dimension = 2;
  struct P {
    double x, y, vx;
    ParticleKind k;
  };
  const P ps[] = {
      {-0.05, 0.25, 1.0, ParticleKind::kInlet},  // A: enters the fluid
      {0.95, 0.75, 1.0, ParticleKind::kFluid},   // B: enters the outlet
      {1.48, 1.25, 1.0, ParticleKind::kOutlet},  // C: farthest: replaces A in the inlet
      {1.30, 1.75, 0.5, ParticleKind::kOutlet},  // D: stays in the outlet
      {1.46, 2.25, 1.0, ParticleKind::kOutlet},  // E: leaves, not needed: shifted back
      {0.02, 2.75, -0.5, ParticleKind::kFluid},  // F: pushed back into the inlet
  };
  for (const P& q : ps) {
    p.positions.insert(p.positions.end(), {q.x, q.y, 0.0});
    p.velocities.insert(p.velocities.end(), {q.vx, 0.0, 0.0});
    p.kinds.push_back(q.k);
    p.masses.push_back(0.01);
    p.densities.push_back(1.0);
  }
  return s;
}

TEST(SdpdOpenBoundary, TransitionsOfOneSubstepByHand) {
  HandMade s = hand_made();
  SdpdBackend b;
  b.initialize(s.model, s.state, {});
  const StepReport rep = b.advance(0, 0.1);
  EXPECT_EQ(rep.substeps, 1u);
  ParticleState p;
  b.read_state(p);
  ASSERT_EQ(p.size(), 6u);
  const ParticleKind kI = ParticleKind::kInlet, kF = ParticleKind::kFluid,
                     kO = ParticleKind::kOutlet;
  const ParticleKind want[] = {kF, kO, kI, kO, kI, kI};
  const double x[] = {0.05, 1.05, 0.05 - 0.5, 1.35, 1.56 - 2.0, -0.03};
  const double y[] = {0.25, 0.75, 0.25, 1.75, 2.25, 2.75};
  const double vx[] = {1.0, 1.0, 1.0, 0.5, 1.0, 1.0};  // inlet: the inflow speed
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(p.kind(i), want[i]) << "particle " << i;
    EXPECT_NEAR(p.positions[3 * i], x[i], 1e-12) << "particle " << i;
    EXPECT_NEAR(p.positions[3 * i + 1], y[i], 1e-12) << "particle " << i;
    EXPECT_NEAR(p.velocities[3 * i], vx[i], 1e-12) << "particle " << i;
    EXPECT_EQ(p.ids[i], i);
  }
  // outlet particles hold the reference density (P = 0)
  EXPECT_EQ(p.densities[1], 1.0);
  EXPECT_EQ(p.densities[3], 1.0);
}

TEST(SdpdOpenBoundary, KindsRejectedWithoutOpenBoundaryAndParticlesOutsideChannel) {
  HandMade s = hand_made();
  s.model.open_boundary.enabled = false;
  SdpdBackend b;
  try {
    b.initialize(s.model, s.state, {});
    FAIL() << "inlet kind accepted without an open boundary";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("needs an open boundary"), std::string::npos) << e.what();
  }
  s = hand_made();
  s.model.open_boundary.inlet_lo = -0.4;  // particle A moved before inlet_lo
  s.state.positions[0] = -0.45;
  try {
    b.initialize(s.model, s.state, {});
    FAIL() << "particle outside [inlet_lo, outlet_hi] accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("outside the open channel"), std::string::npos)
        << e.what();
  }
  s = hand_made();
  s.model.open_boundary.fluid_lo = -0.45;  // inlet length 0.05 < h = 0.2
  try {
    b.initialize(s.model, s.state, {});
    FAIL() << "inlet shorter than h accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("open_boundary.inlet length"), std::string::npos)
        << e.what();
  }
  s = hand_made();
  s.model.box.periodic[0] = true;
  EXPECT_THROW(b.initialize(s.model, s.state, {}), InvalidArgument);
}

OpenChannelSpec threaded_spec() {
  OpenChannelSpec spec;
  spec.ny = 12;
  spec.length = 4.0;  // 1120 particles > kMinParallel
  spec.start_with_profile = true;
  spec.temperature = 1e-4;  // thermal noise on fluid particles
  return spec;
}

struct Trajectory {
  ParticleState state;
  std::uint64_t recycled = 0, entered = 0;
};

Trajectory run_channel(const OpenChannel& c, int steps, SdpdBackend& b) {
  Trajectory t;
  ParticleState prev;
  b.read_state(prev);
  for (int k = 0; k < steps; ++k) {
    b.advance(static_cast<std::uint64_t>(k), 0.05);
    b.read_state(t.state);
    Crossings x;
    count_crossings(prev, t.state, x);
    t.recycled += x.recycled;
    t.entered += x.in;
    prev = t.state;
  }
  (void)c;
  return t;
}

TEST(SdpdOpenBoundary, ThreadCountDoesNotChangeResults) {
#ifdef SADR_HAVE_OPENMP
  const OpenChannel c = make_open_channel(threaded_spec());
  ASSERT_GT(static_cast<std::int64_t>(c.particles.size()), kMinParallel);
  auto run = [&](int threads) {
    omp_set_num_threads(threads);
    SdpdBackend b;
    b.initialize(c.model, c.particles, {});
    return run_channel(c, 8, b);
  };
  const int max_threads = omp_get_max_threads();
  const Trajectory one = run(1), two = run(2);
  omp_set_num_threads(max_threads);
  EXPECT_GT(one.recycled, 0u);  // the run exercises every transition
  EXPECT_GT(one.entered, 0u);
  EXPECT_EQ(one.state.positions, two.state.positions);
  EXPECT_EQ(one.state.velocities, two.state.velocities);
  EXPECT_EQ(one.state.densities, two.state.densities);
  EXPECT_EQ(one.state.kinds, two.state.kinds);
#else
  GTEST_SKIP() << "built without OpenMP";
#endif
}

TEST(SdpdOpenBoundary, SaveRestoreGivesIdenticalTrajectory) {
  OpenChannelSpec spec = threaded_spec();
  spec.length = 2.0;
  const OpenChannel c = make_open_channel(spec);
  SdpdBackend a;
  a.initialize(c.model, c.particles, {});
  for (std::uint64_t k = 0; k < 4; ++k) a.advance(k, 0.05);
  const std::string blob = a.save();
  for (std::uint64_t k = 4; k < 10; ++k) a.advance(k, 0.05);
  SdpdBackend b;
  b.initialize(c.model, c.particles, {});
  b.restore(blob);
  for (std::uint64_t k = 4; k < 10; ++k) b.advance(k, 0.05);
  ParticleState pa, pb;
  a.read_state(pa);
  b.read_state(pb);
  EXPECT_EQ(pa.positions, pb.positions);
  EXPECT_EQ(pa.velocities, pb.velocities);
  EXPECT_EQ(pa.densities, pb.densities);
  EXPECT_EQ(pa.kinds, pb.kinds);
  EXPECT_NE(pa.kinds, c.particles.kinds);  // kinds did change (and were restored)
  // a blob with kinds is refused by a model without an open boundary and vice versa
  FluidModel closed = c.model;
  closed.open_boundary.enabled = false;
  ParticleState fluid_only = c.particles;
  for (auto& k : fluid_only.kinds) {
    if (k != ParticleKind::kWall) k = ParticleKind::kFluid;
  }
  SdpdBackend d;
  d.initialize(closed, fluid_only, {});
  EXPECT_THROW(d.restore(blob), InvalidArgument);
  EXPECT_THROW(a.restore(d.save()), InvalidArgument);
}

TEST(SdpdOpenBoundary, NumberConstantAndFlowStaysInsideOverManyRecycles) {
  OpenChannelSpec spec;
  spec.ny = 6;
  spec.length = 1.5;
  const OpenChannel c = make_open_channel(spec);
  SdpdBackend b;
  b.initialize(c.model, c.particles, {});
  const Trajectory t = run_channel(c, 80, b);  // t = 4: ~2 passes of (L + 2 Lb) / U
  std::size_t nonwall = 0;
  for (auto k : c.particles.kinds) nonwall += k != ParticleKind::kWall;
  EXPECT_EQ(t.state.size(), c.particles.size());
  EXPECT_GT(t.entered, nonwall);  // more than one full pass entered the fluid
  for (std::size_t i = 0; i < t.state.size(); ++i) {
    const double x = t.state.positions[3 * i];
    if (t.state.kind(i) == ParticleKind::kWall) continue;
    EXPECT_GE(x, c.model.open_boundary.inlet_lo);
    EXPECT_LE(x, c.model.open_boundary.outlet_hi);
  }
}

// Reaction sites follow the particles' kinds. The scene labels every non-wall particle
// fluid (as a scene file without inlet/outlet fills does); the backend classifies the buffers
// at initialize() and after every sub-step, and a reaction on `fluid` (the default) must fire
// only where a particle is fluid at the time: deep in the inlet never (C stays 1 exactly),
// inside the fluid all along (C = e^-kt), on particles that entered the fluid meanwhile from
// then on (1 > C > e^-kt). With sites fixed at setup from the scene's labels the first check
// fails; with sites fixed after the first classification the last one does.
TEST(SdpdOpenBoundary, ReactionSitesFollowTheParticlesKinds) {
  OpenChannelSpec spec;
  spec.ny = 4;
  spec.length = 1.0;
  OpenChannel c = make_open_channel(spec);
  for (auto& k : c.particles.kinds) {
    if (k != ParticleKind::kWall) k = ParticleKind::kFluid;
  }
  c.model.species.push_back({"A", 0.0, true, {}, {}});  // kappa = 0: only the reaction acts
  ReactionSpec r;
  r.def.name = "decay";
  r.reactants = {{0, 1}};
  r.def.rate = 1.0;  // kinds empty = fluid only
  c.model.reactions.push_back(r);
  SdpdBackend b;
  b.initialize(c.model, c.particles, {std::vector<double>(c.particles.size(), 1.0)});
  ParticleState start;
  b.read_state(start);
  const double t_end = 0.2;
  for (std::uint64_t k = 0; k < 10; ++k) b.advance(k, t_end / 10);
  ParticleState end;
  b.read_state(end);
  const auto& conc = b.concentrations(0);
  std::size_t deep_inlet = 0, interior = 0, entered = 0;
  for (std::size_t i = 0; i < end.size(); ++i) {
    if (start.kind(i) == ParticleKind::kWall) continue;
    const double x0 = start.positions[3 * i];
    if (x0 < -0.4) {  // moves at most 1.5 * 0.2 = 0.3: inlet all along
      ++deep_inlet;
      EXPECT_EQ(conc[i], 1.0) << "inlet particle " << i << " at x0 = " << x0;
    } else if (x0 > 0.3 && x0 < 0.5) {  // fluid all along
      ++interior;
      EXPECT_NEAR(conc[i], std::exp(-t_end), 1e-3) << "fluid particle " << i;
    } else if (start.kind(i) == ParticleKind::kInlet && end.kind(i) == ParticleKind::kFluid) {
      ++entered;
      EXPECT_LT(conc[i], 1.0) << "particle " << i << " entered the fluid but never reacted";
      EXPECT_GT(conc[i], std::exp(-t_end) + 1e-3) << "particle " << i << " reacted as an inlet";
    }
  }
  EXPECT_GT(deep_inlet, 0u);
  EXPECT_GT(interior, 0u);
  EXPECT_GT(entered, 0u);
}

}  // namespace
}  // namespace sadr::fluid::test
