// SPDX-License-Identifier: MIT
// ssa_service: the exact spatial SSA (NSM) over ZeroMQ. See sadr/wire/service_main.hpp
// for the command line and exit codes.
#include "sadr/common/openmp_env.hpp"
#include "sadr/ssa/ssa_service.hpp"
#include "sadr/wire/service_main.hpp"

int main(int argc, char** argv) {
  sadr::ensure_passive_openmp_wait(argv);  // the graph build may use OpenMP: see openmp_env.hpp
  return sadr::wire::run_service_main(argc, argv, sadr::common::v1::SERVICE_KIND_SSA, [] {
    return std::make_unique<sadr::ssa::SsaServiceHandler>();
  });
}
