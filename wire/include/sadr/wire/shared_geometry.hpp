// SPDX-License-Identifier: MIT
/// \file shared_geometry.hpp
/// The per-step particle geometry (positions, densities, masses) in a POSIX
/// shared-memory segment, for services on the same host.
///
/// Why: every coupling step fluid_service hands ~40 bytes per particle to
/// ssa_service. Inline in the protocol that is serialised, copied through two
/// sockets and parsed twice (fluid -> orchestrator -> ssa): ~9 user-space and 4
/// kernel copies, 0.5 ms (embedded) to 2 ms (processes) per step at 1e4
/// particles (bench/results/README-coupled.md). When the orchestrator launched
/// the services itself (processes or --embedded), it creates one segment per
/// run and names it in the Advance requests; fluid_service writes the geometry
/// into it after the step, ssa_service reads it from there, and only the name
/// and a generation number travel in the messages. Remote services (tcp, other
/// hosts) keep the inline path.
///
/// Layout (version 3): a 64-byte header (magic, version, capacity N, last
/// generation written), two 32-byte slot headers (generation, count, dimension,
/// has-kinds flag, time), then two slots of 3N positions, N densities, N masses
/// each (doubles, native byte order: same host), then two slots of N kinds (one
/// byte each, padded to 8: kinds change along an open boundary, so the SSA's
/// reactions can follow them). Generation g goes to slot g % 2 (a double
/// buffer): with the orchestrator's overlapped loop, fluid_service writes
/// generation g + 1 while ssa_service may still read generation g, and a write
/// never touches the slot of the previous generation. A read checks the slot's
/// generation before and after copying (a sequence lock), so reading a
/// generation that was overwritten (g + 2) fails loudly instead of returning
/// mixed data. The segment is created 0600 with O_EXCL; the orchestrator
/// unlinks the name once both services have mapped it (the mappings stay
/// valid), so a crash later leaves nothing behind in /dev/shm.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "sadr/common/particle_state.hpp"

namespace sadr::wire {

/// Unlinks the geometry segments that process `pid` created
/// ("/sadr-geometry-<pid>-*"); returns how many. For a service whose parent
/// died and for sadr's sweep of dead runs.
std::size_t remove_segments_of(long pid);
/// Unlinks the segments of every process of this user that no longer runs
/// (kill(pid, 0) fails with ESRCH); returns how many.
std::size_t remove_segments_of_dead_processes();

class SharedGeometry {
 public:
  /// A new segment for `capacity` particles (name: "/sadr-geometry-<pid>-<k>").
  /// The memory is reserved at once (posix_fallocate). Throws sadr::Error
  /// (kInternal) naming the system error, e.g. a full or too small /dev/shm; the
  /// orchestrator then sends the geometry inline.
  static SharedGeometry create(std::size_t capacity);
  /// Maps an existing segment read-write; checks the header and the size and
  /// throws InvalidArgument naming `where`, the segment and what is wrong.
  static SharedGeometry open(const std::string& name, std::string_view where);

  SharedGeometry() = default;
  SharedGeometry(SharedGeometry&& other) noexcept;
  SharedGeometry& operator=(SharedGeometry&& other) noexcept;
  SharedGeometry(const SharedGeometry&) = delete;
  SharedGeometry& operator=(const SharedGeometry&) = delete;
  ~SharedGeometry();

  [[nodiscard]] bool valid() const { return base_ != nullptr; }
  [[nodiscard]] const std::string& name() const { return name_; }
  [[nodiscard]] std::size_t capacity() const;
  /// Removes the name (mappings, including this one, stay valid). Idempotent.
  void unlink();

  /// Writes p's dimension, positions, densities, masses, kinds (when p has them)
  /// and `time` as the next generation g (into slot g % 2, leaving generation
  /// g - 1 readable) and returns g. Throws InvalidArgument if p has more
  /// particles than the segment holds.
  std::uint64_t write(const ParticleState& p, double time);
  /// Reads what write() stored into out (dimension, positions, densities, masses,
  /// kinds if written, else from `previous`; ids from `previous`, velocities
  /// empty) and validates it (finish_geometry). Throws InvalidArgument naming
  /// `where` if the slot of `generation` does not hold it (a stale, overwritten or
  /// foreign generation, also when it is overwritten during the copy), the count
  /// differs from previous.size(), or a kind is invalid or turns a wall into a
  /// non-wall particle or back.
  void read(std::uint64_t generation, const ParticleState& previous, ParticleState& out,
            std::string_view where) const;

 private:
  struct Header;
  struct Slot;
  Header* header() const;
  std::uint8_t* kinds(std::uint64_t generation) const;
  Slot* slot(std::uint64_t generation) const;
  double* data(std::uint64_t generation) const;

  std::string name_;
  void* base_ = nullptr;
  std::size_t bytes_ = 0;
  bool owner_ = false;  ///< created here: unlink() on destruction if not done yet
};

}  // namespace sadr::wire
