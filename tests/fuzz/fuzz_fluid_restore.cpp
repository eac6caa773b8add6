// SPDX-License-Identifier: MIT
// Fuzz target: fluid_service snapshot restore. Input: [backend byte][blob]; the
// byte picks kBackends[b % 2] (static, sdpd), the rest is the blob of a
// Restore after Init of kSmallScene; a restored state is advanced once and
// snapshot again (fuzz_restore.hpp). Seeds: real blobs from make_seeds.
#include "fuzz_restore.hpp"
#include "sadr/fluid/fluid_service.hpp"

namespace {
using Handler = sadr::fluid::FluidServiceHandler;
using Req = sadr::fluid::v1::FluidRequest;
using Rep = sadr::fluid::v1::FluidReply;
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::size_t b = data[0] % 2;
  static const sadr::common::v1::Snapshot envelopes[] = {
      sadr::fuzz::snapshot_envelope<Handler, Req, Rep>(sadr::fuzz::small_inits(0).fluid),
      sadr::fuzz::snapshot_envelope<Handler, Req, Rep>(sadr::fuzz::small_inits(1).fluid)};
  const std::string_view blob(reinterpret_cast<const char*>(data) + 1, size - 1);
  sadr::fuzz::restore_and_step<Handler, Req, Rep>(sadr::fuzz::small_inits(b).fluid, envelopes[b],
                                                  blob, "fluid_service restore");
  return 0;
}
