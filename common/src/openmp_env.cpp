// SPDX-License-Identifier: MIT
#include "sadr/common/openmp_env.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "sadr/common/status.hpp"

namespace sadr {

void ensure_passive_openmp_wait(char** argv) {
  // The user's choice (or already done before the re-exec).
  if (std::getenv("OMP_WAIT_POLICY") != nullptr || std::getenv("GOMP_SPINCOUNT") != nullptr) return;
  if (::setenv("OMP_WAIT_POLICY", "passive", 0) != 0) return;
  ::execv("/proc/self/exe", argv);
  // Still here: the re-exec failed. Children inherit the setting; this process
  // keeps libgomp's default, which costs speed only on busy machines.
  std::fprintf(stderr, "sadr: note: could not re-execute with OMP_WAIT_POLICY=passive (%s)\n",
               std::strerror(errno));
}

int service_threads_from_env(const char* name) {
  const char* v = std::getenv(name);
  if (v == nullptr || *v == '\0') return 0;
  char* end = nullptr;
  const long n = std::strtol(v, &end, 10);
  if (*end != '\0' || n < 1 || n > 4096) {
    throw InvalidArgument(std::string(name) + " = '" + v + "' (allowed: 1..4096, or unset)",
                          {{"field", name}, {"value", v}});
  }
  return static_cast<int>(n);
}

}  // namespace sadr
