// SPDX-License-Identifier: MIT
/// \file machine_limits.hpp
/// What this machine offers a run (memory, the per-process limit, free disk) and the measured
/// memory per particle of each process (bench/memory_per_particle.py). The scene loader refuses
/// a lattice that cannot fit; work_estimate.hpp builds the whole estimate on these.
#pragma once

#include <filesystem>
#include <string>

namespace sadr::orchestrator {

/// What this machine offers a run.
struct MachineLimits {
  double memory_bytes = 0;     ///< min(physical memory, cgroup memory.max): all processes
  std::string memory_source;   ///< which of those it is
  double process_bytes = 0;    ///< RLIMIT_AS (per process; infinity when unlimited)
  double free_disk_bytes = 0;  ///< free bytes where the output goes (or its nearest parent)
};
/// Reads the limits of this machine; `output` need not exist yet.
MachineLimits machine_limits(const std::filesystem::path& output);

/// Peak resident bytes of one process: base + per_particle * N.
struct MemoryModel {
  double base = 0;
  double per_particle = 0;
  [[nodiscard]] double at(double particles) const { return base + per_particle * particles; }
};
/// Measured models (bench/memory_per_particle.py; docs/cli.md lists them).
MemoryModel fluid_memory(const std::string& backend, int dimension);
MemoryModel ssa_memory(int dimension);
MemoryModel orchestrator_memory(const std::string& backend);
/// Whether the fluid backend moves particles (its schema capability; true for an unknown name).
bool moves_particles(const std::string& backend);

}  // namespace sadr::orchestrator
