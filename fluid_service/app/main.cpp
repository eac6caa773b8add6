// SPDX-License-Identifier: MIT
// fluid_service: a particle fluid (SDPD, static, ...) over ZeroMQ. See
// sadr/wire/service_main.hpp for the command line and exit codes.
#include "sadr/common/openmp_env.hpp"
#include "sadr/fluid/fluid_service.hpp"
#include "sadr/wire/service_main.hpp"

int main(int argc, char** argv) {
  sadr::ensure_passive_openmp_wait(argv);  // see openmp_env.hpp
  return sadr::wire::run_service_main(argc, argv, sadr::common::v1::SERVICE_KIND_FLUID, [] {
    return std::make_unique<sadr::fluid::FluidServiceHandler>();
  });
}
