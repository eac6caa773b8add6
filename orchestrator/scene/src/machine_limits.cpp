// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/machine_limits.hpp"

#include <sys/resource.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <limits>

#include "sadr/fluid/backend_schema.hpp"

namespace sadr::orchestrator {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// The backend's schema memory figures (sdpd's defaults for an unknown name: the loader has
/// refused it already).
sadr::fluid::schema::MemoryPerParticle backend_memory(const std::string& backend) {
  const auto* b = sadr::fluid::schema::find(backend);
  return b ? b->memory : sadr::fluid::schema::MemoryPerParticle{};
}

}  // namespace

// Bytes per particle: the backend's schema entry (measured by bench/memory_per_particle.py, peak
// RSS at 1e5 and 4e5 particles, the slope rounded up; docs/cli.md has the table). The base
// (libraries, thread stacks) was 9-16 MiB per process.
MemoryModel fluid_memory(const std::string& backend, int dimension) {
  const auto d = static_cast<std::size_t>(std::clamp(dimension, 1, 3) - 1);
  return {16e6, backend_memory(backend).fluid_service[d]};
}

MemoryModel ssa_memory(int dimension) {
  return {16e6, dimension == 1 ? 510.0 : 1230.0};
}

MemoryModel orchestrator_memory(const std::string& backend) {
  return {16e6, backend_memory(backend).sadr};
}

bool moves_particles(const std::string& backend) {
  const auto* b = sadr::fluid::schema::find(backend);
  return b == nullptr || b->capabilities.moves_particles;
}

MachineLimits machine_limits(const std::filesystem::path& output) {
  MachineLimits m;
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  m.memory_bytes = pages > 0 && page > 0 ? static_cast<double>(pages) * page : kInf;
  m.memory_source = "physical memory";
  std::ifstream cg("/sys/fs/cgroup/memory.max");
  std::string text;
  if (cg >> text && text != "max") {
    const double v = std::strtod(text.c_str(), nullptr);
    if (v > 0 && v < m.memory_bytes) {
      m.memory_bytes = v;
      m.memory_source = "cgroup memory.max";
    }
  }
  // Operator caps (a quota, a share of a node): never raise what the machine has.
  auto cap = [](const char* name, double& value, std::string* source) {
    const char* v = std::getenv(name);
    const double x = v ? std::strtod(v, nullptr) : 0.0;
    if (x > 0 && x < value) {
      value = x;
      if (source) *source = name;
    }
  };
  cap("SADR_MEMORY_LIMIT", m.memory_bytes, &m.memory_source);
  rlimit rl{};
  m.process_bytes = getrlimit(RLIMIT_AS, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY
                        ? static_cast<double>(rl.rlim_cur)
                        : kInf;
  std::error_code ec;
  std::filesystem::path dir = std::filesystem::absolute(output, ec);
  while (!dir.empty() && !std::filesystem::exists(dir, ec) && dir != dir.parent_path()) {
    dir = dir.parent_path();
  }
  struct statvfs st {};
  m.free_disk_bytes = statvfs(dir.c_str(), &st) == 0
                          ? static_cast<double>(st.f_bavail) * static_cast<double>(st.f_frsize)
                          : kInf;
  cap("SADR_DISK_LIMIT", m.free_disk_bytes, nullptr);
  return m;
}

}  // namespace sadr::orchestrator
