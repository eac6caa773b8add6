// SPDX-License-Identifier: MIT
/// \file flow_tape.hpp
/// The flow replay file (flow_replay.bin in an ensemble's output folder): every
/// call the coupling loop made of the fluid service in one pass, with what it
/// answered, so that the other realizations take the answers from the file
/// instead of stepping the fluid again (plan.hpp, flow replay).
///
/// Layout (little-endian, fixed-size integers, IEEE doubles as their bits):
///   header: "SADRFLOW", u32 version, u32 n + n bytes of the fluid key (fluid_key():
///           what the fluid service receives, the coupling schedule, the output times),
///           u64 particles, u64 records, u64 FNV-1a 64 of the header bytes before it
///   record: u32 "REC1", u64 ordinal (0, 1, ...), u64 payload size, payload,
///           u64 FNV-1a 64 of the ordinal, size and payload bytes
///   payload: u8 call, u64 step index, f64 dt, u8 want geometry, the species
///           names asked for, f64 time, u32 sub-steps, f64 smallest stability
///           limit met and its name (u32 n + n bytes), u8 moved, u8 has particles,
///           [particles: u32 dimension, then positions, velocities, densities,
///           masses, kinds, ids, each as u64 count + values], then the
///           concentrations (u32 count; each a name and u64 count + doubles).
/// The writer writes to `<path>.partial` and renames it only when finished (the
/// header's record count filled in), so a file under the final name is complete.
/// Every read is checked: a bad magic, version, hash, checksum or a short read
/// is an InvalidArgument naming the file, the record and what differs; a file
/// recorded for another fluid key is refused before any record is read.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "sadr/common/particle_state.hpp"

namespace sadr::orchestrator {

/// The file's name in an ensemble's output folder.
inline constexpr std::string_view kFlowTapeName = "flow_replay.bin";
inline constexpr std::uint32_t kFlowTapeVersion = 3;  ///< 3: the header holds the fluid key

/// Which FluidService call a record holds (service_interfaces.hpp).
enum class FlowCall : std::uint8_t { kAdvance = 1, kGeometry = 2, kFrame = 3 };
const char* to_string(FlowCall call);

/// One fluid call: what was asked, then what the fluid answered.
struct FlowRecord {
  FlowCall call = FlowCall::kAdvance;
  // Asked:
  std::uint64_t step_index = 0;      ///< advance: the fluid call's step index
  double dt = 0.0;                   ///< advance: the stage length [time]
  bool want_geometry = false;        ///< advance: the geometry after the stage
  std::vector<std::string> species;  ///< advance: return_concentrations; frame: species
  // Answered:
  double time = 0.0;           ///< advance: time after the stage [time]
  std::uint32_t substeps = 0;  ///< advance
  /// advance: the smallest stability limit the stage met [time] (FluidStep) and its name
  double stable_time_step = 0.0;
  std::string limiting_criterion;
  bool moved = false;          ///< advance: particles moved
  bool has_particles = false;  ///< `particles` holds an answer
  ParticleState particles;     ///< geometry (advance, geometry) or frame state
  std::vector<std::pair<std::string, std::vector<double>>> concentrations;
};

struct FlowTapeHeader {
  std::string fluid_key;  ///< fluid_key() of the recorded scene (scene_messages.hpp)
  std::uint64_t particles = 0;
  std::uint64_t records = 0;
};

/// Where a reader is: the next record's ordinal and byte offset.
struct FlowTapePosition {
  std::uint64_t record = 0;
  std::uint64_t offset = 0;
};

class FlowTapeWriter {
 public:
  /// Creates `<path>.partial` (replacing one left by an earlier attempt).
  FlowTapeWriter(std::filesystem::path path, std::string fluid_key, std::uint64_t particles);
  ~FlowTapeWriter();  ///< unfinished: removes the partial file
  FlowTapeWriter(const FlowTapeWriter&) = delete;
  FlowTapeWriter& operator=(const FlowTapeWriter&) = delete;

  void append(const FlowRecord& record);
  /// Writes the record count into the header, flushes and renames to `path`.
  /// @return the file size [bytes]
  std::uint64_t finish();
  [[nodiscard]] std::uint64_t records() const { return header_.records; }

 private:
  std::filesystem::path path_, partial_;
  FlowTapeHeader header_;
  std::ofstream out_;
  bool finished_ = false;
};

class FlowTapeReader {
 public:
  /// Opens and checks the header; `expected_fluid_key` (unless empty) must match.
  FlowTapeReader(std::filesystem::path path, const std::string& expected_fluid_key);

  [[nodiscard]] const FlowTapeHeader& header() const { return header_; }
  [[nodiscard]] FlowTapePosition position() const { return pos_; }
  [[nodiscard]] bool at_end() const { return pos_.record >= header_.records; }
  /// The next record, its checksum verified.
  FlowRecord next();
  /// Continues at `p` (a position() of this file); the record there must carry p.record.
  void seek(const FlowTapePosition& p);

 private:
  [[noreturn]] void fail(const std::string& what) const;
  std::filesystem::path path_;
  std::ifstream in_;
  FlowTapeHeader header_;
  FlowTapePosition pos_;
  std::uint64_t first_offset_ = 0;
  std::uint64_t file_size_ = 0;
};

}  // namespace sadr::orchestrator
