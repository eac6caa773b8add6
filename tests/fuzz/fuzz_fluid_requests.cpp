// SPDX-License-Identifier: MIT
// Fuzz target: every request type of fluid_service, in-process (no sockets).
// The input is a sequence of serialized sadr.fluid.v1.FluidRequest bodies
// (split_chunks), handed to a fresh FluidServiceHandler in order. Seeds: Init
// (static and sdpd), Advance, GetState, SetSpecies, Snapshot, Restore, Shutdown
// sequences from make_seeds.
#include "fuzz_messages.hpp"
#include "sadr/fluid/fluid_service.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  sadr::fluid::FluidServiceHandler handler;
  bool shutdown = false;
  for (const auto chunk : sadr::fuzz::split_chunks(data, size)) {
    const std::string reply_bytes = handler.handle(chunk, shutdown);
    sadr::fluid::v1::FluidReply reply;
    if (!reply.ParseFromString(reply_bytes)) std::abort();
    sadr::fuzz::require_diagnosed(reply.status(), "fluid_service");
    if (shutdown) break;
  }
  return 0;
}
