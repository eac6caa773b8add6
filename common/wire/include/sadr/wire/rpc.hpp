// SPDX-License-Identifier: MIT
/// \file rpc.hpp
/// Request/reply over ZeroMQ with protobuf bodies (wire protocol v1).
///
/// Every message is two ZeroMQ frames: [FrameHeader][body]. The header names
/// the protocol version and the body's fully qualified protobuf type, so a
/// mismatch is refused before the body is parsed. A client must complete a
/// handshake (HandshakeRequest -> HandshakeReply) before any other request.
/// Errors detected by the framing layer are answered with a
/// sadr.common.v1.Status body; the client turns that into a sadr::Error.
///
/// ZeroMQ is an implementation detail: no header of this library includes it.
/// Endpoints: "tcp://127.0.0.1:*" (ephemeral port, read back with endpoint()),
/// "ipc:///path", or "inproc://name" (threads of one process; all sockets of a
/// process share one ZeroMQ context, so inproc works across threads).
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>

#include "sadr/common/status.hpp"
#include "sadr/common/v1/frame.pb.h"

namespace google::protobuf {
class Message;
}

namespace sadr::wire {

/// Name used in messages: "fluid_service" / "ssa_service".
std::string_view service_name(common::v1::ServiceKind kind);

/// What a service does with requests that passed the framing checks.
class RequestHandler {
 public:
  virtual ~RequestHandler() = default;
  /// Fully qualified type of the request body, e.g. "sadr.fluid.v1.FluidRequest".
  virtual std::string_view request_type() const = 0;
  /// Fully qualified type of the reply body.
  virtual std::string_view reply_type() const = 0;
  /// Handles one serialized request (a view into the received frame: no copy);
  /// returns the serialized reply, which is sent without another copy. Must not
  /// throw: errors go into the reply's Status. Sets `shutdown` to stop serving.
  virtual std::string handle(std::string_view body, bool& shutdown) = 0;
};

struct ServerOptions {
  std::string endpoint = "tcp://127.0.0.1:*";  ///< where to bind
  common::v1::ServiceKind kind = common::v1::SERVICE_KIND_UNSPECIFIED;
  std::int64_t max_message_bytes = std::int64_t{1}
                                   << 31;        ///< larger messages are dropped by ZeroMQ
  std::chrono::milliseconds poll_interval{100};  ///< how often serve() checks the stop flag
  /// Non-empty: only clients presenting this secret connect (ZeroMQ PLAIN
  /// checked by a ZAP handler in this process); others fail in the ZeroMQ
  /// handshake and never reach serve(). Services launched by sadr get a
  /// per-run secret through SADR_RUN_SECRET (service_main.hpp).
  std::string secret;
};

/// Clients of `endpoint` created from now on present `secret` (PLAIN); an
/// empty secret forgets the endpoint. Set by sadr for the services it launches.
void set_client_secret(const std::string& endpoint, const std::string& secret);
/// At most `limit` characters of `text`, with "... (N bytes)" when cut: for
/// echoing or logging what a peer sent.
std::string shorten(std::string_view text, std::size_t limit = 80);

/// A bound server socket (ROUTER) that checks frames and handshakes.
class RpcServer {
 public:
  /// Binds immediately; throws sadr::Error(kUnavailable) if the endpoint cannot be bound.
  explicit RpcServer(ServerOptions options);
  ~RpcServer();
  RpcServer(const RpcServer&) = delete;
  RpcServer& operator=(const RpcServer&) = delete;

  /// The bound endpoint with the ephemeral port resolved.
  [[nodiscard]] std::string endpoint() const;
  /// Serves requests until the handler asks to shut down or `stop` becomes true.
  void serve(RequestHandler& handler, const std::atomic<bool>* stop = nullptr);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// A client connection (REQ, relaxed) with a per-call timeout.
class RpcClient {
 public:
  /// `peer_name` appears in error messages ("ssa_service at ipc:///tmp/x").
  RpcClient(std::string endpoint, std::string peer_name,
            std::chrono::milliseconds timeout = std::chrono::seconds(60));
  ~RpcClient();
  RpcClient(const RpcClient&) = delete;
  RpcClient& operator=(const RpcClient&) = delete;

  /// Performs the handshake. Throws sadr::Error(kProtocolMismatch) with the
  /// server's explanation if it refuses, kDeadlineExceeded on timeout.
  common::v1::HandshakeReply handshake(common::v1::ServiceKind expected,
                                       std::uint32_t protocol_version);
  /// Sends `request`, waits for a reply of the type of `reply` and parses it.
  /// Throws sadr::Error on timeout, framing errors or an unparsable reply.
  void call(const google::protobuf::Message& request, google::protobuf::Message& reply);
  /// Low level: sends arbitrary frames (tests use this to send malformed
  /// messages). Returns the raw reply frames header and body.
  void call_raw(const std::string& header, const std::string& body, std::string& reply_header,
                std::string& reply_body);
  [[nodiscard]] const std::string& endpoint() const { return endpoint_; }
  void set_timeout(std::chrono::milliseconds timeout) { timeout_ = timeout; }
  /// Called about every 200 ms while waiting for a reply; it may throw (e.g.
  /// when the service's process has exited) to abort the wait early.
  void set_liveness_check(std::function<void()> check) { liveness_ = std::move(check); }

 private:
  /// Sends [header][body] (the body without a copy) and waits for the 2-frame
  /// reply, which stays in impl_ (read in place, not copied) until the next call.
  void exchange(std::string header, std::string body);

  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string endpoint_;
  std::string peer_name_;
  std::chrono::milliseconds timeout_;
  std::uint64_t sequence_ = 0;
  std::function<void()> liveness_;
};

}  // namespace sadr::wire
