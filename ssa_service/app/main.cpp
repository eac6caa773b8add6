// SPDX-License-Identifier: MIT
// ssa_service: the exact spatial SSA (NSM) over ZeroMQ. See sadr/wire/service_main.hpp
// for the command line and exit codes.
#include "sadr/ssa/ssa_service.hpp"
#include "sadr/wire/service_main.hpp"

int main(int argc, char** argv) {
  return sadr::wire::run_service_main(argc, argv, sadr::common::v1::SERVICE_KIND_SSA, [] {
    return std::make_unique<sadr::ssa::SsaServiceHandler>();
  });
}
