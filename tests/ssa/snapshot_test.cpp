// SPDX-License-Identifier: MIT
// Snapshot at a random time -> restore -> identical trajectory (counts, events, time),
// across graph rebuilds, reservoirs, Neumann sources and region-restricted reactions.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "sadr/common/status.hpp"
#include "sadr/ssa/nsm_solver.hpp"
#include "ssa_test_support.hpp"

namespace sadr::ssa {
namespace {

Model rich_model() {
  Model m = testing::diffusion_model(testing::make_box(2, 8.0, false), 2.0, 0.5);
  m.species = {{"A", 0.5}, {"B", 0.3}, {"C", 0.0}};
  m.reactions = {{"bind", {{0, 1}, {1, 1}}, {{2, 1}}, 0.3, {}, {}},
                 {"unbind", {{2, 1}}, {{0, 1}, {1, 1}}, 0.2, {}, {}},
                 {"dimer", {{0, 2}}, {{2, 1}}, 0.05, {}, {10, 11, 12, 20, 21}}};
  m.reservoirs = {{0, 20.0, {}}};
  m.neumann = {{1, 2.0}};
  return m;
}

ParticleState particles(std::uint64_t seed) {
  ParticleState p = testing::make_lattice(2, 8, 1.0, 0.3, 0.2, seed);
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.positions[3 * i] < 1.0) p.kinds[i] = ParticleKind::kWall;
  }
  return p;
}

struct Outcome {
  std::vector<std::int64_t> counts;
  std::uint64_t events;
  double time;
  std::string blob;
};

/// The schedule after the snapshot: advance, move particles, advance.
Outcome continue_run(NsmSolver& s, double t_snap) {
  s.advance(t_snap + 0.7);
  s.update_graph(particles(2));
  s.advance(t_snap + 2.0);
  Outcome o{{}, s.events(), s.time(), s.save()};
  for (int sp = 0; sp < 3; ++sp) {
    o.counts.insert(o.counts.end(), s.counts(sp).begin(), s.counts(sp).end());
  }
  return o;
}

TEST(Snapshot, RestoreContinuesBitIdentically) {
  std::mt19937_64 gen(2718);
  for (int trial = 0; trial < 3; ++trial) {
    const double t_snap = std::uniform_real_distribution<double>(0.5, 2.0)(gen);
    NsmSolver a(rich_model(), 100 + trial);
    a.update_graph(particles(1));
    a.set_counts(0, std::vector<std::int64_t>(64, 10));
    a.set_counts(1, std::vector<std::int64_t>(64, 5));
    a.advance(t_snap);
    const std::string blob = a.save();
    ASSERT_GT(a.events(), 100u);
    const Outcome ref = continue_run(a, t_snap);

    NsmSolver b(rich_model(), 999);  // another seed: everything must come from the blob
    b.restore(blob);
    EXPECT_EQ(b.time(), t_snap);
    const Outcome got = continue_run(b, t_snap);
    EXPECT_EQ(got.counts, ref.counts);
    EXPECT_EQ(got.events, ref.events);
    EXPECT_EQ(got.time, ref.time);
    EXPECT_EQ(got.blob, ref.blob);  // the complete state, byte for byte

    a.restore(blob);  // restoring into a used solver works too
    EXPECT_EQ(continue_run(a, t_snap).counts, ref.counts);
  }
}

TEST(Snapshot, RejectsCorruptionAndOtherModels) {
  NsmSolver a(rich_model(), 1);
  a.update_graph(particles(1));
  a.advance(0.5);
  std::string blob = a.save();
  std::string bad = blob;
  bad[bad.size() / 2] ^= 0x5A;
  EXPECT_THROW(a.restore(bad), sadr::InvalidArgument);
  EXPECT_THROW(a.restore(blob.substr(0, blob.size() - 9)), sadr::InvalidArgument);
  EXPECT_THROW(a.restore("garbage"), sadr::InvalidArgument);
  Model other = rich_model();
  other.reactions[0].def.rate = 0.31;
  NsmSolver c(other, 1);
  EXPECT_THROW(c.restore(blob), sadr::InvalidArgument);
  EXPECT_NO_THROW(a.restore(blob));
  EXPECT_EQ(a.time(), 0.5);
}

// FNV-1a 64, the snapshot checksum (as in the core's blob.hpp).
std::uint64_t fnv1a(const std::string& s) {
  std::uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : s) h = (h ^ c) * 1099511628211ULL;
  return h;
}

/// The same state in the version 1 layout (the 4-ary heap solver's): the event
/// times as {f64 time, u32 voxel, u32 pad} records, here in reverse voxel order
/// (any permutation is a valid reading: heap order is one).
std::string as_version1(const std::string& v2, std::size_t voxels) {
  const std::size_t times_at = v2.size() - 8 - 8 * voxels;  // vec<f64> payload, then checksum
  std::string out = v2.substr(0, times_at);                 // up to and with the length field
  const std::uint32_t version = 1;
  std::memcpy(out.data() + 8, &version, 4);  // after the 8-byte magic
  for (std::size_t k = voxels; k-- > 0;) {
    double t;
    std::memcpy(&t, v2.data() + times_at + 8 * k, 8);
    const auto voxel = static_cast<std::uint32_t>(k);
    const std::uint32_t pad = 0;
    out.append(reinterpret_cast<const char*>(&t), 8);
    out.append(reinterpret_cast<const char*>(&voxel), 4);
    out.append(reinterpret_cast<const char*>(&pad), 4);
  }
  const std::uint64_t sum = fnv1a(out);
  out.append(reinterpret_cast<const char*>(&sum), 8);
  return out;
}

TEST(Snapshot, ReadsVersion1Blobs) {
  NsmSolver a(rich_model(), 5);
  a.update_graph(particles(1));
  a.set_counts(0, std::vector<std::int64_t>(64, 10));
  a.advance(0.8);
  const std::string blob = a.save();
  const Outcome ref = continue_run(a, 0.8);
  NsmSolver b(rich_model(), 6);
  b.restore(as_version1(blob, 64));
  const Outcome got = continue_run(b, 0.8);
  EXPECT_EQ(got.counts, ref.counts);
  EXPECT_EQ(got.events, ref.events);
  EXPECT_EQ(got.blob, ref.blob);
  // A version 1 blob naming a voxel twice is rejected.
  std::string dup = as_version1(blob, 64);
  const std::size_t first = dup.size() - 8 - 16 * 64;
  std::memcpy(dup.data() + first + 16 + 8, dup.data() + first + 8, 4);
  dup.resize(dup.size() - 8);
  const std::uint64_t sum = fnv1a(dup);
  dup.append(reinterpret_cast<const char*>(&sum), 8);
  EXPECT_THROW(b.restore(dup), sadr::InvalidArgument);
  // Unknown versions name the supported ones.
  std::string v9 = blob;
  const std::uint32_t nine = 9;
  std::memcpy(v9.data() + 8, &nine, 4);
  EXPECT_THROW(b.restore(v9), sadr::InvalidArgument);
}

}  // namespace
}  // namespace sadr::ssa
