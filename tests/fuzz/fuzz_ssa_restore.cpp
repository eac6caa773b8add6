// SPDX-License-Identifier: MIT
// Fuzz target: ssa_service snapshot restore. Input: the blob of a Restore after
// Init of kSmallScene; a restored state is advanced once and snapshot again
// (fuzz_restore.hpp). Seeds: real NSM blobs from make_seeds.
#include "fuzz_restore.hpp"
#include "sadr/ssa/ssa_service.hpp"

namespace {
using Handler = sadr::ssa::SsaServiceHandler;
using Req = sadr::ssa::v1::SsaRequest;
using Rep = sadr::ssa::v1::SsaReply;
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const sadr::common::v1::Snapshot envelope =
      sadr::fuzz::snapshot_envelope<Handler, Req, Rep>(sadr::fuzz::small_inits(0).ssa);
  const std::string_view blob(reinterpret_cast<const char*>(data), size);
  sadr::fuzz::restore_and_step<Handler, Req, Rep>(sadr::fuzz::small_inits(0).ssa, envelope, blob,
                                                  "ssa_service restore");
  return 0;
}
