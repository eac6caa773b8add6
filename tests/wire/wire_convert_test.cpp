// SPDX-License-Identifier: MIT
// Protocol round trips: domain -> proto -> bytes -> proto -> domain is exact.
#include "sadr/wire/convert.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "sadr/common/v1/snapshot.pb.h"

namespace sadr::wire {
namespace {

ParticleState sample(std::size_t n) {
  ParticleState s;
  s.dimension = 3;
  s.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (int a = 0; a < 3; ++a) {
      s.positions[3 * i + a] = std::sin(0.1 * i + a) * 1e-3;
      s.velocities[3 * i + a] = std::cos(0.3 * i - a) * 1e-7;
    }
    s.densities[i] = 1000.0 + 1e-9 * i;
    s.masses[i] = 1e-9 * (1 + i % 3);
    s.kinds[i] = static_cast<ParticleKind>(i % 4);
    s.ids[i] = 1000 + i;
  }
  return s;
}

TEST(WireConvert, ParticleStateRoundTripIsBitExact) {
  const ParticleState in = sample(257);
  common::v1::ParticleState p;
  to_proto(in, p);
  std::string bytes;
  ASSERT_TRUE(p.SerializeToString(&bytes));
  common::v1::ParticleState q;
  ASSERT_TRUE(q.ParseFromString(bytes));
  const ParticleState out = from_proto(q, "test");
  EXPECT_EQ(out.dimension, in.dimension);
  EXPECT_EQ(out.positions, in.positions);
  EXPECT_EQ(out.velocities, in.velocities);
  EXPECT_EQ(out.densities, in.densities);
  EXPECT_EQ(out.masses, in.masses);
  EXPECT_EQ(out.kinds, in.kinds);
  EXPECT_EQ(out.ids, in.ids);
}

TEST(WireConvert, PackedArraysAreCompact) {
  // Packed repeated doubles: ~8 bytes per value plus a few bytes per field.
  const ParticleState in = sample(1000);
  common::v1::ParticleState p;
  to_proto(in, p, /*with_velocities=*/false);
  const std::size_t values = in.positions.size() + in.densities.size() + in.masses.size();
  EXPECT_LT(p.ByteSizeLong(), values * 8 + 1000 * 3 /*kinds*/ + 1000 * 3 /*ids*/ + 64);
  EXPECT_EQ(p.velocities_size(), 0);
}

TEST(WireConvert, InvalidStateIsRefusedNamingTheField) {
  ParticleState in = sample(4);
  common::v1::ParticleState p;
  to_proto(in, p);
  p.set_masses(2, -3.0);
  try {
    from_proto(p, "ssa.init.particles");
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_STREQ(e.what(), "ssa.init.particles: particle 2: mass = -3 (must be finite and > 0)");
  }
  to_proto(in, p);
  p.set_kinds(1, 7);
  EXPECT_THROW(from_proto(p, "x"), InvalidArgument);
  to_proto(in, p);
  p.mutable_densities()->RemoveLast();
  EXPECT_THROW(from_proto(p, "x"), InvalidArgument);
}

// The per-step geometry (Advance(return_state) -> ssa Advance) carries kinds (they change
// along an open boundary) but leaves ids and velocities out; the reader takes the ids, and
// the kinds when absent, from the previous state.
TEST(WireConvert, GeometryRoundTripCarriesKindsAndKeepsIdsOfThePreviousState) {
  const ParticleState previous = sample(33);
  ParticleState moved = previous;
  for (double& x : moved.positions) x += 0.25;
  for (double& r : moved.densities) r *= 1.5;
  // fluid -> inlet -> outlet -> fluid; walls (kind 1) stay walls
  for (auto& k : moved.kinds) {
    if (k == ParticleKind::kFluid)
      k = ParticleKind::kInlet;
    else if (k == ParticleKind::kInlet)
      k = ParticleKind::kOutlet;
    else if (k == ParticleKind::kOutlet)
      k = ParticleKind::kFluid;
  }
  common::v1::ParticleState p;
  geometry_to_proto(moved, p);
  EXPECT_EQ(p.kinds_size(), 33);
  EXPECT_EQ(p.ids_size(), 0);
  EXPECT_EQ(p.velocities_size(), 0);
  std::string bytes;
  ASSERT_TRUE(p.SerializeToString(&bytes));
  common::v1::ParticleState q;
  ASSERT_TRUE(q.ParseFromString(bytes));
  ParticleState out = sample(2);  // buffers of another size are reused and resized
  state_from_proto(q, previous, out, "advance.particles");
  EXPECT_EQ(out.dimension, moved.dimension);
  EXPECT_EQ(out.positions, moved.positions);
  EXPECT_EQ(out.densities, moved.densities);
  EXPECT_EQ(out.masses, moved.masses);
  EXPECT_EQ(out.kinds, moved.kinds);
  EXPECT_NE(out.kinds, previous.kinds);
  EXPECT_EQ(out.ids, previous.ids);
  EXPECT_TRUE(out.velocities.empty());
  // Without kinds (an older fluid service) the previous kinds are kept.
  q.clear_kinds();
  state_from_proto(q, previous, out, "advance.particles");
  EXPECT_EQ(out.kinds, previous.kinds);
}

/// The message state_from_proto throws for p ("<no error>" if it accepts p).
std::string geometry_error(const common::v1::ParticleState& p, const ParticleState& previous) {
  ParticleState out;
  try {
    state_from_proto(p, previous, out, "advance.particles");
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "<no error>";
}

TEST(WireConvert, GeometryThatTurnsAWallIntoFluidOrHasABadKindIsRefused) {
  const ParticleState previous = sample(8);  // particle 1 is a wall
  common::v1::ParticleState p;
  geometry_to_proto(previous, p);
  EXPECT_EQ(geometry_error(p, previous), "<no error>");
  p.set_kinds(1, 0);
  EXPECT_EQ(geometry_error(p, previous),
            "advance.particles: particle 1 changed kind from wall to fluid (allowed: fluid, "
            "inlet and outlet change into each other; wall particles stay walls)");
  geometry_to_proto(previous, p);
  p.set_kinds(0, 1);  // fluid -> wall
  EXPECT_EQ(geometry_error(p, previous),
            "advance.particles: particle 0 changed kind from fluid to wall (allowed: fluid, "
            "inlet and outlet change into each other; wall particles stay walls)");
  geometry_to_proto(previous, p);
  p.set_kinds(2, 300);  // (must not wrap into a valid kind)
  EXPECT_EQ(geometry_error(p, previous),
            "advance.particles: kinds[2] = 300 (allowed: 0 fluid, 1 wall, 2 inlet, 3 outlet)");
}

TEST(WireConvert, GeometryWithTheWrongCountOrBadValuesIsRefused) {
  const ParticleState previous = sample(8);
  common::v1::ParticleState p;
  geometry_to_proto(sample(7), p);
  ParticleState out;
  try {
    state_from_proto(p, previous, out, "advance.particles");
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_STREQ(e.what(),
                 "advance.particles: 7 densities, expected one per particle (8; the particle set "
                 "cannot change after Init)");
  }
  geometry_to_proto(previous, p);
  p.set_positions(5, std::nan(""));
  try {
    state_from_proto(p, previous, out, "advance.particles");
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_STREQ(e.what(), "advance.particles: particle 1: position[2] = nan (must be finite)");
  }
}

TEST(WireConvert, StatusAndBoxRoundTrip) {
  const Status s{StatusCode::kNumericalFailure, "NaN", {{"particle", "7"}, {"field", "rho"}}};
  common::v1::Status p;
  to_proto(s, p);
  const Status t = from_proto(p);
  EXPECT_EQ(t.code, s.code);
  EXPECT_EQ(t.message, s.message);
  EXPECT_EQ(t.details, s.details);

  Box b;
  b.dimension = 2;
  b.hi = {2, 3, 1};
  b.periodic = {true, false, false};
  common::v1::Box pb;
  to_proto(b, pb);
  const Box c = from_proto(pb, "box");
  EXPECT_EQ(c.dimension, 2);
  EXPECT_EQ(c.hi, b.hi);
  EXPECT_EQ(c.periodic, b.periodic);
  pb.set_upper(0, -1);
  EXPECT_THROW(from_proto(pb, "box"), InvalidArgument);
}

TEST(WireConvert, SnapshotCarriesBinaryBlobs) {
  common::v1::Snapshot snap;
  std::string blob(256, '\0');
  for (int i = 0; i < 256; ++i) blob[i] = static_cast<char>(i);
  snap.set_format("sadr.test");
  snap.set_format_version(3);
  snap.set_blob(blob);
  (*snap.mutable_metadata())["seed"] = "42";
  std::string bytes;
  ASSERT_TRUE(snap.SerializeToString(&bytes));
  common::v1::Snapshot back;
  ASSERT_TRUE(back.ParseFromString(bytes));
  EXPECT_EQ(back.blob(), blob);
  EXPECT_EQ(back.metadata().at("seed"), "42");
}

}  // namespace
}  // namespace sadr::wire
