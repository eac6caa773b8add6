// SPDX-License-Identifier: MIT
// Fuzz target: frame decoding of the RPC server (rpc.hpp), through its public
// functions. One RpcServer serves on inproc:// in a thread for the whole
// process, with a handler that only checks and echoes; every input is a
// sequence of [FrameHeader bytes][body bytes] pairs (split_chunks) sent by a
// fresh RpcClient (a new peer: no handshake carried over) with call_raw. Every
// request must get a reply; a reply's header must parse, and a refusal must
// be a sadr.common.v1.Status. Seeds: handshakes, requests before and after a
// handshake, wrong versions and types (make_seeds).
#include <atomic>
#include <memory>
#include <thread>

#include "fuzz_support.hpp"
#include "sadr/common/v1/frame.pb.h"
#include "sadr/common/v1/status.pb.h"
#include "sadr/wire/rpc.hpp"

namespace {

/// Accepts any body of its request type and answers with its size.
class EchoHandler : public sadr::wire::RequestHandler {
 public:
  std::string_view request_type() const override { return "sadr.fuzz.Request"; }
  std::string_view reply_type() const override { return "sadr.common.v1.Status"; }
  std::string handle(std::string_view body, bool& shutdown) override {
    shutdown = false;  // a fuzzed Shutdown must not stop the shared server
    sadr::common::v1::Status st;
    st.set_message(std::to_string(body.size()));
    return st.SerializeAsString();
  }
};

struct Server {
  EchoHandler handler;
  sadr::wire::RpcServer server{[] {
    sadr::wire::ServerOptions o;
    o.endpoint = "inproc://sadr-fuzz-frame";
    o.kind = sadr::common::v1::SERVICE_KIND_SSA;
    o.poll_interval = std::chrono::milliseconds(10);
    return o;
  }()};
  std::thread thread{[this] { server.serve(handler); }};
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static auto* server = new Server;  // never destroyed: serves until the process ends
  const auto chunks = sadr::fuzz::split_chunks(data, size, 12);
  std::unique_ptr<sadr::wire::RpcClient> made;
  // A new client (socket) per input: at thousands of inputs per second ZeroMQ's
  // reaper can fall behind, and socket creation then throws zmq::error_t (not a
  // sadr::Error: issue #18 note in tests/fuzz/README.md). Give it time, then retry.
  for (int attempt = 0; !made; ++attempt) {
    try {
      made = std::make_unique<sadr::wire::RpcClient>("inproc://sadr-fuzz-frame", "fuzz peer",
                                                     std::chrono::seconds(5));
    } catch (const std::exception& e) {
      static bool told = false;
      if (!told)
        std::fprintf(stderr, "fuzz: client creation failed once (retrying): %s\n", e.what());
      told = true;
      if (attempt == 100) {
        std::fprintf(stderr, "fuzz: cannot create a client: %s\n", e.what());
        std::abort();
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
  auto& client = *made;
  for (std::size_t k = 0; k + 1 < chunks.size(); k += 2) {
    std::string header;
    std::string body;
    try {
      client.call_raw(std::string(chunks[k]), std::string(chunks[k + 1]), header, body);
    } catch (const sadr::Error& e) {
      std::fprintf(stderr, "fuzz: no reply: %s\n", e.what());
      std::abort();  // the server must answer every two-frame message
    }
    sadr::common::v1::FrameHeader h;
    if (!h.ParseFromString(header)) std::abort();
    if (h.message_type() == "sadr.common.v1.Status") {
      sadr::common::v1::Status st;
      if (!st.ParseFromString(body)) std::abort();
    }
  }
  (void)server;
  return 0;
}
