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

TEST(SharedGeometry, WriteThenReadIsBitExactAndKeepsKindsAndIds) {
  SharedGeometry owner = SharedGeometry::create(300);
  ASSERT_TRUE(owner.valid());
  EXPECT_EQ(owner.capacity(), 300u);
  SharedGeometry writer = SharedGeometry::open(owner.name(), "test.writer");
  SharedGeometry reader = SharedGeometry::open(owner.name(), "test.reader");
  const ParticleState previous = sample(257, 0.0);
  for (int step = 1; step <= 3; ++step) {
    const ParticleState moved = sample(257, 0.01 * step);
    const std::uint64_t gen = writer.write(moved, 0.1 * step);
    EXPECT_EQ(gen, static_cast<std::uint64_t>(step));
    ParticleState out;
    reader.read(gen, previous, out, "test.read");
    EXPECT_EQ(out.dimension, 2);
    ASSERT_EQ(out.size(), moved.size());
    EXPECT_EQ(std::memcmp(out.positions.data(), moved.positions.data(), 8 * 3 * 257), 0);
    EXPECT_EQ(std::memcmp(out.densities.data(), moved.densities.data(), 8 * 257), 0);
    EXPECT_EQ(std::memcmp(out.masses.data(), moved.masses.data(), 8 * 257), 0);
    EXPECT_EQ(out.kinds, previous.kinds);
    EXPECT_EQ(out.ids, previous.ids);
    EXPECT_TRUE(out.velocities.empty());
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
