// SPDX-License-Identifier: MIT
// The shared-memory geometry segment (fluid_service -> ssa_service on one host).
#include "sadr/wire/shared_geometry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>

#include "sadr/common/status.hpp"

namespace sadr::wire {
namespace {

ParticleState sample(std::size_t n, double shift) {
  ParticleState s;
  s.dimension = 2;
  s.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    s.positions[3 * i] = std::sin(0.1 * i) + shift;
    s.positions[3 * i + 1] = std::cos(0.1 * i);
    s.densities[i] = 1.0 + 1e-3 * i;
    s.masses[i] = 0.5 + 1e-4 * i;
    s.kinds[i] = static_cast<ParticleKind>(i % 2);
    s.ids[i] = 100 + i;
  }
  return s;
}

bool exists_in_dev_shm(const std::string& name) {
  return std::filesystem::exists("/dev/shm" + name);
}

TEST(SharedGeometry, WriteThenReadIsBitExactCarriesKindsAndKeepsIds) {
  SharedGeometry owner = SharedGeometry::create(300);
  ASSERT_TRUE(owner.valid());
  EXPECT_EQ(owner.capacity(), 300u);
  SharedGeometry writer = SharedGeometry::open(owner.name(), "test.writer");
  SharedGeometry reader = SharedGeometry::open(owner.name(), "test.reader");
  const ParticleState previous = sample(257, 0.0);
  for (int step = 1; step <= 3; ++step) {
    ParticleState moved = sample(257, 0.01 * step);
    // non-wall particles cycle fluid -> inlet -> outlet (an open boundary); walls stay
    for (std::size_t i = 0; i < moved.size(); ++i) {
      if (moved.kinds[i] == ParticleKind::kWall) continue;
      constexpr ParticleKind kCycle[3] = {ParticleKind::kFluid, ParticleKind::kInlet,
                                          ParticleKind::kOutlet};
      moved.kinds[i] = kCycle[(i / 2 + static_cast<std::size_t>(step)) % 3];
    }
    const std::uint64_t gen = writer.write(moved, 0.1 * step);
    EXPECT_EQ(gen, static_cast<std::uint64_t>(step));
    ParticleState out;
    reader.read(gen, previous, out, "test.read");
    EXPECT_EQ(out.dimension, 2);
    ASSERT_EQ(out.size(), moved.size());
    EXPECT_EQ(std::memcmp(out.positions.data(), moved.positions.data(), 8 * 3 * 257), 0);
    EXPECT_EQ(std::memcmp(out.densities.data(), moved.densities.data(), 8 * 257), 0);
    EXPECT_EQ(std::memcmp(out.masses.data(), moved.masses.data(), 8 * 257), 0);
    EXPECT_EQ(out.kinds, moved.kinds);
    EXPECT_EQ(out.ids, previous.ids);
    EXPECT_TRUE(out.velocities.empty());
  }
  // A write without kinds leaves the previous ones; a wall that turns into fluid is refused.
  ParticleState bare = sample(257, 0.5);
  bare.kinds.clear();
  ParticleState out;
  reader.read(writer.write(bare, 1.0), previous, out, "test.read");
  EXPECT_EQ(out.kinds, previous.kinds);
  ParticleState bad = sample(257, 0.6);
  bad.kinds[1] = ParticleKind::kFluid;  // a wall in `previous`
  try {
    reader.read(writer.write(bad, 1.1), previous, out, "test.read");
    FAIL() << "a wall turned into fluid was accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("test.read: particle 1 changed kind from wall to fluid"),
              std::string::npos)
        << e.what();
  }
}

TEST(SharedGeometry, StaleGenerationAndChangedCountAreRefused) {
  SharedGeometry owner = SharedGeometry::create(10);
  SharedGeometry peer = SharedGeometry::open(owner.name(), "test");
  const ParticleState p = sample(10, 0.0);
  const std::uint64_t gen = peer.write(p, 0.0);
  ParticleState out;
  try {
    owner.read(gen + 1, p, out, "advance.geometry_shm");
    FAIL() << "a stale generation was accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("advance.geometry_shm"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("stale"), std::string::npos) << e.what();
  }
  EXPECT_THROW(owner.read(gen, sample(9, 0.0), out, "x"), InvalidArgument);  // count changed
  EXPECT_THROW(peer.write(sample(11, 0.0), 0.0), InvalidArgument);           // over capacity
}

// The double buffer (orchestrator overlap: the fluid writes generation g + 1
// while the SSA may still read generation g).
TEST(SharedGeometry, PreviousGenerationStaysReadableAfterTheNextWrite) {
  SharedGeometry owner = SharedGeometry::create(64);
  SharedGeometry writer = SharedGeometry::open(owner.name(), "test.writer");
  SharedGeometry reader = SharedGeometry::open(owner.name(), "test.reader");
  const ParticleState previous = sample(50, 0.0);
  const ParticleState p1 = sample(50, 0.25), p2 = sample(50, 0.5), p3 = sample(50, 0.75);
  const std::uint64_t g1 = writer.write(p1, 0.1);
  const std::uint64_t g2 = writer.write(p2, 0.2);
  EXPECT_EQ(g1, 1u);
  EXPECT_EQ(g2, 2u);
  ParticleState out;
  reader.read(g1, previous, out, "test.read");  // written before g2: still intact
  EXPECT_EQ(std::memcmp(out.positions.data(), p1.positions.data(), 8 * 3 * 50), 0);
  EXPECT_EQ(std::memcmp(out.densities.data(), p1.densities.data(), 8 * 50), 0);
  EXPECT_EQ(std::memcmp(out.masses.data(), p1.masses.data(), 8 * 50), 0);
  reader.read(g2, previous, out, "test.read");
  EXPECT_EQ(std::memcmp(out.positions.data(), p2.positions.data(), 8 * 3 * 50), 0);
  // g3 reuses g1's slot: g1 is gone and must fail loudly, g2 and g3 read.
  const std::uint64_t g3 = writer.write(p3, 0.3);
  EXPECT_EQ(g3, 3u);
  try {
    reader.read(g1, previous, out, "advance.geometry_shm");
    FAIL() << "an overwritten generation was accepted";
  } catch (const InvalidArgument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("advance.geometry_shm"), std::string::npos) << what;
    EXPECT_NE(what.find("holds generation 3"), std::string::npos) << what;
  }
  reader.read(g2, previous, out, "test.read");
  EXPECT_EQ(std::memcmp(out.positions.data(), p2.positions.data(), 8 * 3 * 50), 0);
  reader.read(g3, previous, out, "test.read");
  EXPECT_EQ(std::memcmp(out.positions.data(), p3.positions.data(), 8 * 3 * 50), 0);
  // A generation not written yet, and generation 0, are refused too.
  EXPECT_THROW(reader.read(g3 + 1, previous, out, "x"), InvalidArgument);
  EXPECT_THROW(reader.read(0, previous, out, "x"), InvalidArgument);
}

TEST(SharedGeometry, TheTwoSlotsDoNotOverlap) {
  // Capacity-sized writes: the last particle of one slot must not clobber the
  // first of the other (a layout error would show as mixed data).
  SharedGeometry owner = SharedGeometry::create(33);
  SharedGeometry peer = SharedGeometry::open(owner.name(), "test");
  const ParticleState previous = sample(33, 0.0);
  const ParticleState a = sample(33, 1.0), b = sample(33, -1.0);
  const std::uint64_t ga = peer.write(a, 0.0);
  const std::uint64_t gb = peer.write(b, 0.0);
  ParticleState out;
  owner.read(ga, previous, out, "test");
  EXPECT_EQ(std::memcmp(out.positions.data(), a.positions.data(), 8 * 3 * 33), 0);
  EXPECT_EQ(std::memcmp(out.densities.data(), a.densities.data(), 8 * 33), 0);
  EXPECT_EQ(std::memcmp(out.masses.data(), a.masses.data(), 8 * 33), 0);
  owner.read(gb, previous, out, "test");
  EXPECT_EQ(std::memcmp(out.positions.data(), b.positions.data(), 8 * 3 * 33), 0);
  EXPECT_EQ(std::memcmp(out.masses.data(), b.masses.data(), 8 * 33), 0);
}

TEST(SharedGeometry, BadNamesAndMissingSegmentsNameTheField) {
  for (const std::string name : {"", "/etc-passwd", "/sadr-a/b", "sadr-x"}) {
    EXPECT_THROW(SharedGeometry::open(name, "advance.geometry_shm"), InvalidArgument) << name;
  }
  try {
    SharedGeometry::open("/sadr-geometry-does-not-exist", "advance.geometry_shm");
    FAIL() << "a missing segment was opened";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("advance.geometry_shm = '/sadr-geometry-does-not-exist'"),
              std::string::npos)
        << e.what();
  }
}

TEST(SharedGeometry, UnlinkRemovesTheNameButNotTheMappings) {
  std::string name;
  {
    SharedGeometry owner = SharedGeometry::create(4);
    name = owner.name();
    SharedGeometry peer = SharedGeometry::open(name, "test");
    EXPECT_TRUE(exists_in_dev_shm(name));
    owner.unlink();
    EXPECT_FALSE(exists_in_dev_shm(name));
    EXPECT_THROW(SharedGeometry::open(name, "test"), InvalidArgument);
    const ParticleState p = sample(4, 0.0);
    ParticleState out;
    owner.read(peer.write(p, 1.0), p, out, "test");  // both mappings still work
    EXPECT_EQ(out.positions, p.positions);
  }
  // An owner destroyed without unlink() removes the name itself.
  {
    SharedGeometry owner = SharedGeometry::create(4);
    name = owner.name();
    EXPECT_TRUE(exists_in_dev_shm(name));
  }
  EXPECT_FALSE(exists_in_dev_shm(name));
}

}  // namespace
}  // namespace sadr::wire
