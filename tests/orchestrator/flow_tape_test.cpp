// SPDX-License-Identifier: MIT
// The flow replay file (flow_tape.hpp): round trip, seek, and every kind of
// damage refused with the record named (corrupt byte, truncation, wrong scene,
// an unfinished file never under the final name).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "sadr/common/status.hpp"
#include "sadr/orchestrator/flow_tape.hpp"

namespace sadr::orchestrator {
namespace {
namespace fs = std::filesystem;

fs::path scratch_file(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("sadr-flow-tape-" + std::to_string(getpid()));
  fs::create_directories(d);
  fs::remove(d / name);
  return d / name;
}

FlowRecord advance_record(std::uint64_t step, bool with_geometry) {
  FlowRecord r;
  r.call = FlowCall::kAdvance;
  r.step_index = step;
  r.dt = 0.02 * (1.0 + 1e-12 * static_cast<double>(step));
  r.want_geometry = with_geometry;
  r.species = {"C"};
  r.time = 0.1 + 0.02 * static_cast<double>(step);
  r.substeps = 3;
  r.stable_time_step = 1.0 / 3.0;
  r.limiting_criterion = "reaction";
  r.moved = true;
  r.has_particles = with_geometry;
  if (with_geometry) {
    r.particles.dimension = 2;
    r.particles.positions = {0.1, 0.2, 0.0, 1.0 / 3.0, 0.5, 0.0};
    r.particles.densities = {1.0, 0.99999999999};
    r.particles.masses = {0.0025, 0.0025};
    r.particles.kinds = {ParticleKind::kFluid, ParticleKind::kWall};
  }
  r.concentrations = {{"C", {2.5, -0.0}}};
  return r;
}

FlowRecord frame_record() {
  FlowRecord r;
  r.call = FlowCall::kFrame;
  r.species = {"C", "D"};
  r.has_particles = true;
  r.particles.dimension = 3;
  r.particles.positions = {1, 2, 3};
  r.particles.velocities = {4, 5, 6};
  r.particles.densities = {7};
  r.particles.masses = {8};
  r.particles.ids = {42};
  r.concentrations = {{"C", {1e-300}}, {"D", {9.5}}};
  return r;
}

/// Bit for bit (so -0.0 and 0.0 differ).
template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

bool same(const FlowRecord& a, const FlowRecord& b) {
  const ParticleState &p = a.particles, &q = b.particles;
  bool ok = a.call == b.call && a.step_index == b.step_index && same_bits<double>({a.dt}, {b.dt}) &&
            a.want_geometry == b.want_geometry && a.species == b.species &&
            same_bits<double>({a.time}, {b.time}) && a.substeps == b.substeps &&
            same_bits<double>({a.stable_time_step}, {b.stable_time_step}) &&
            a.limiting_criterion == b.limiting_criterion && a.moved == b.moved &&
            a.has_particles == b.has_particles && p.dimension == q.dimension &&
            same_bits(p.positions, q.positions) && same_bits(p.velocities, q.velocities) &&
            same_bits(p.densities, q.densities) && same_bits(p.masses, q.masses) &&
            same_bits(p.kinds, q.kinds) && same_bits(p.ids, q.ids) &&
            a.concentrations.size() == b.concentrations.size();
  for (std::size_t k = 0; ok && k < a.concentrations.size(); ++k) {
    ok = a.concentrations[k].first == b.concentrations[k].first &&
         same_bits(a.concentrations[k].second, b.concentrations[k].second);
  }
  return ok;
}

fs::path write_tape(const std::string& name, std::uint64_t n = 5) {
  const fs::path p = scratch_file(name);
  FlowTapeWriter w(p, "fnv1a64:0123456789abcdef", 2);
  for (std::uint64_t k = 0; k < n; ++k) w.append(advance_record(k, k % 2 == 0));
  w.append(frame_record());
  EXPECT_GT(w.finish(), 100u);
  return p;
}

std::string error_of(const fs::path& p, const std::string& hash = "") {
  try {
    FlowTapeReader r(p, hash);
    while (!r.at_end()) r.next();
    r.next();
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "";
}

void flip_byte(const fs::path& p, std::uint64_t offset) {
  std::fstream f(p, std::ios::in | std::ios::out | std::ios::binary);
  f.seekg(static_cast<std::streamoff>(offset));
  char c = 0;
  f.get(c);
  f.seekp(static_cast<std::streamoff>(offset));
  f.put(static_cast<char>(c ^ 0x10));
}

TEST(FlowTape, RoundTripGivesTheSameRecordsBitForBit) {
  const fs::path p = write_tape("round.bin");
  FlowTapeReader r(p, "fnv1a64:0123456789abcdef");
  EXPECT_EQ(r.header().particles, 2u);
  EXPECT_EQ(r.header().records, 6u);
  for (std::uint64_t k = 0; k < 5; ++k)
    EXPECT_TRUE(same(r.next(), advance_record(k, k % 2 == 0))) << k;
  EXPECT_TRUE(same(r.next(), frame_record()));
  EXPECT_TRUE(r.at_end());
  EXPECT_FALSE(fs::exists(p.string() + ".partial"));
}

TEST(FlowTape, SeekContinuesAtARememberedPosition) {
  const fs::path p = write_tape("seek.bin");
  FlowTapeReader r(p, "");
  r.next();
  r.next();
  const FlowTapePosition at = r.position();
  EXPECT_EQ(at.record, 2u);
  EXPECT_TRUE(same(r.next(), advance_record(2, true)));
  FlowTapeReader other(p, "");
  other.seek(at);
  EXPECT_TRUE(same(other.next(), advance_record(2, true)));
  // A position whose ordinal is not the record found there is refused.
  FlowTapeReader wrong(p, "");
  wrong.seek({3, at.offset});
  EXPECT_THROW(wrong.next(), InvalidArgument);
}

TEST(FlowTape, ACorruptedRecordIsDetectedByItsChecksum) {
  const fs::path p = write_tape("corrupt.bin");
  FlowTapeReader r(p, "");
  r.next();
  const std::uint64_t second = r.position().offset;
  flip_byte(p, second + 40);  // inside record 1's payload
  const std::string e = error_of(p);
  EXPECT_NE(e.find("checksum mismatch at record 1 of 6"), std::string::npos) << e;
}

TEST(FlowTape, ATruncatedFileIsDetected) {
  const fs::path p = write_tape("truncated.bin");
  fs::resize_file(p, fs::file_size(p) - 30);  // the last record loses its tail
  const std::string e = error_of(p);
  EXPECT_NE(e.find("truncated at record 5 of 6"), std::string::npos) << e;
  fs::resize_file(p, 30);  // inside the header
  EXPECT_NE(error_of(p).find("truncated in its header"), std::string::npos) << error_of(p);
}

TEST(FlowTape, ACorruptHeaderAnotherSceneAndReadingPastTheEndAreRefused) {
  const fs::path p = write_tape("header.bin");
  EXPECT_NE(error_of(p, "fnv1a64:ffffffffffffffff").find("recorded for the fluid"),
            std::string::npos);
  EXPECT_NE(error_of(p).find("has no record 6 of 6"), std::string::npos) << error_of(p);
  flip_byte(p, 50);  // the record count
  EXPECT_NE(error_of(p).find("header checksum mismatch"), std::string::npos) << error_of(p);
  const fs::path q = scratch_file("not.bin");
  std::ofstream(q) << "hello, this is not a tape at all";
  EXPECT_NE(error_of(q).find("not a flow replay file"), std::string::npos);
}

TEST(FlowTape, AnUnfinishedFileIsRemovedAndNeverUnderTheFinalName) {
  const fs::path p = scratch_file("unfinished.bin");
  {
    FlowTapeWriter w(p, "h", 1);
    w.append(advance_record(0, false));
    EXPECT_TRUE(fs::exists(p.string() + ".partial"));
  }
  EXPECT_FALSE(fs::exists(p));
  EXPECT_FALSE(fs::exists(p.string() + ".partial"));
}

}  // namespace
}  // namespace sadr::orchestrator
