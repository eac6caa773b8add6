// SPDX-License-Identifier: MIT
// The framing layer in one process (inproc and tcp loopback): handshake,
// version and type checks, refusal of requests before the handshake.
#include "sadr/wire/rpc.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

#include "sadr/common/v1/snapshot.pb.h"
#include "sadr/common/v1/status.pb.h"
#include "sadr/common/version.hpp"
#include "sadr/wire/convert.hpp"

namespace sadr::wire {
namespace {

using common::v1::ServiceKind;

/// Echoes a Snapshot with its blob reversed; "stop" in the format shuts down.
class EchoHandler : public RequestHandler {
 public:
  std::string_view request_type() const override { return "sadr.common.v1.Snapshot"; }
  std::string_view reply_type() const override { return "sadr.common.v1.Snapshot"; }
  std::string handle(std::string_view body, bool& shutdown) override {
    common::v1::Snapshot s;
    s.ParseFromArray(body.data(), static_cast<int>(body.size()));
    std::string b = s.blob();
    std::reverse(b.begin(), b.end());
    s.set_blob(b);
    shutdown = s.format() == "stop";
    std::string out;
    s.SerializeToString(&out);
    return out;
  }
};

class RpcFixture : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    ServerOptions o;
    o.endpoint = GetParam();
    o.kind = common::v1::SERVICE_KIND_SSA;
    o.poll_interval = std::chrono::milliseconds(20);
    server_ = std::make_unique<RpcServer>(o);
    endpoint_ = server_->endpoint();
    thread_ = std::thread([this] {
      server_->serve(handler_, &stop_);
      served_ = true;
    });
  }
  void TearDown() override {
    stop_ = true;
    thread_.join();
  }
  EchoHandler handler_;
  std::unique_ptr<RpcServer> server_;
  std::string endpoint_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> served_{false};  ///< serve() has returned
  std::thread thread_;
};

TEST_P(RpcFixture, HandshakeThenCall) {
  RpcClient c(endpoint_, "ssa_service", std::chrono::seconds(5));
  const auto rep = c.handshake(common::v1::SERVICE_KIND_SSA, kProtocolVersion);
  EXPECT_EQ(rep.kind(), common::v1::SERVICE_KIND_SSA);
  EXPECT_EQ(rep.protocol_version(), kProtocolVersion);
  common::v1::Snapshot req, out;
  req.set_blob("abc");
  c.call(req, out);
  EXPECT_EQ(out.blob(), "cba");
}

TEST_P(RpcFixture, WrongVersionIsRefusedSayingExpectedAndReceived) {
  RpcClient c(endpoint_, "ssa_service", std::chrono::seconds(5));
  try {
    c.handshake(common::v1::SERVICE_KIND_SSA, 99);
    FAIL() << "handshake with v99 must be refused";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), StatusCode::kProtocolMismatch);
    const std::string m = e.what();
    EXPECT_NE(m.find("speaks sadr wire protocol v" + std::to_string(kProtocolVersion)),
              std::string::npos)
        << m;
    EXPECT_NE(m.find("asked for v99"), std::string::npos) << m;
  }
  // Still refused for a normal request: the handshake never completed.
  common::v1::Snapshot req, out;
  try {
    c.call(req, out);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), StatusCode::kFailedPrecondition);
    EXPECT_NE(std::string(e.what()).find("no handshake"), std::string::npos);
  }
}

TEST_P(RpcFixture, WrongHeaderVersionAndMalformedFramesAreRefused) {
  RpcClient c(endpoint_, "ssa_service", std::chrono::seconds(5));
  common::v1::FrameHeader h;
  h.set_protocol_version(kProtocolVersion + 1);
  h.set_message_type("sadr.common.v1.HandshakeRequest");
  std::string hb, rh, rb;
  h.SerializeToString(&hb);
  c.call_raw(hb, "", rh, rb);
  common::v1::FrameHeader reply_header;
  ASSERT_TRUE(reply_header.ParseFromString(rh));
  EXPECT_EQ(reply_header.message_type(), "sadr.common.v1.Status");
  common::v1::Status st;
  ASSERT_TRUE(st.ParseFromString(rb));
  EXPECT_EQ(st.code(), common::v1::STATUS_CODE_PROTOCOL_MISMATCH);
  EXPECT_NE(st.message().find("speaks sadr wire protocol v" + std::to_string(kProtocolVersion) +
                              ", the request declared v" + std::to_string(kProtocolVersion + 1)),
            std::string::npos)
      << st.message();

  c.call_raw(std::string("\xff\xff\xff", 3), "junk", rh, rb);
  ASSERT_TRUE(st.ParseFromString(rb));
  EXPECT_EQ(st.code(), common::v1::STATUS_CODE_PROTOCOL_MISMATCH);
  EXPECT_NE(st.message().find("malformed frame header"), std::string::npos) << st.message();

  // A malformed handshake body.
  h.set_protocol_version(kProtocolVersion);
  h.SerializeToString(&hb);
  c.call_raw(hb, std::string("\x08\xff", 2), rh, rb);
  common::v1::HandshakeReply hr;
  ASSERT_TRUE(hr.ParseFromString(rb));
  EXPECT_EQ(hr.status().code(), common::v1::STATUS_CODE_INVALID_ARGUMENT);
  EXPECT_NE(hr.status().message().find("malformed handshake"), std::string::npos);
}

TEST_P(RpcFixture, WrongServiceKindAndMessageTypeAreRefused) {
  RpcClient c(endpoint_, "fluid_service", std::chrono::seconds(5));
  try {
    c.handshake(common::v1::SERVICE_KIND_FLUID, kProtocolVersion);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("this endpoint is ssa_service, the client expected "
                                         "fluid_service"),
              std::string::npos)
        << e.what();
  }
  c.handshake(common::v1::SERVICE_KIND_UNSPECIFIED, kProtocolVersion);
  common::v1::Status wrong;
  common::v1::Snapshot out;
  try {
    c.call(wrong, out);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), StatusCode::kProtocolMismatch);
    EXPECT_NE(std::string(e.what()).find("unexpected message type 'sadr.common.v1.Status'"),
              std::string::npos)
        << e.what();
  }
}

TEST_P(RpcFixture, HandlerCanShutDownTheServer) {
  RpcClient c(endpoint_, "ssa_service", std::chrono::seconds(5));
  c.handshake(common::v1::SERVICE_KIND_SSA, kProtocolVersion);
  common::v1::Snapshot req, out;
  req.set_format("stop");
  req.set_blob("abc");
  c.call(req, out);
  EXPECT_EQ(out.blob(), "cba") << "the request that shuts the server down is answered";
  // serve() returns by itself (stop_ is never set here): waited for with a deadline, so a
  // server that keeps serving fails the test instead of hanging it.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (!served_ && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_TRUE(served_) << "serve() did not return after the handler asked to shut down";
  EXPECT_FALSE(stop_);
  thread_.join();
  thread_ = std::thread([] {});
}

INSTANTIATE_TEST_SUITE_P(Transports, RpcFixture,
                         ::testing::Values("inproc://sadr-wire-test", "tcp://127.0.0.1:*"),
                         [](const auto& param_info) {
                           return param_info.index == 0 ? "inproc" : "tcp";
                         });

TEST(RpcClient, TimeoutNamesThePeer) {
  // Nothing listens here; REQ connects lazily and the call times out.
  RpcClient c("tcp://127.0.0.1:1", "fluid_service", std::chrono::milliseconds(200));
  try {
    c.handshake(common::v1::SERVICE_KIND_FLUID, kProtocolVersion);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), StatusCode::kDeadlineExceeded);
    EXPECT_NE(std::string(e.what()).find("fluid_service at tcp://127.0.0.1:1 did not answer"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace sadr::wire
