// SPDX-License-Identifier: MIT
// Fuzz target: every request type of ssa_service, in-process (no sockets). The
// input is a sequence of serialized sadr.ssa.v1.SsaRequest bodies
// (split_chunks), handed to a fresh SsaServiceHandler in order, as the RPC
// server would after the handshake. Seeds: Init, Advance, GetCounts, Snapshot,
// Restore, Shutdown sequences from make_seeds.
#include "fuzz_messages.hpp"
#include "sadr/ssa/ssa_service.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  sadr::ssa::SsaServiceHandler handler;
  bool shutdown = false;
  for (const auto chunk : sadr::fuzz::split_chunks(data, size)) {
    const std::string reply_bytes = handler.handle(chunk, shutdown);
    sadr::ssa::v1::SsaReply reply;
    if (!reply.ParseFromString(reply_bytes)) std::abort();  // the handler's own reply
    sadr::fuzz::require_diagnosed(reply.status(), "ssa_service");
    if (shutdown) break;
  }
  return 0;
}
