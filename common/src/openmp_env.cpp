// SPDX-License-Identifier: MIT
#include "sadr/common/openmp_env.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

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

}  // namespace sadr
