// SPDX-License-Identifier: MIT
/// \file rpc.hpp
/// Request/reply over ZeroMQ with protobuf bodies (wire protocol v1).
///
/// Every message is [FrameHeader][body...]: one header frame, then the body in
/// one or more frames of at most kMaxFrameBytes each (a body up to 4 MiB is a
/// single frame: such messages are unchanged since v1). The header names
/// the protocol version and the body's fully qualified protobuf type, so a
/// mismatch is refused before the body is parsed. A client must complete a
/// handshake (HandshakeRequest -> HandshakeReply) before any other request.
/// Errors detected by the framing layer are answered with a
/// sadr.common.v1.Status body; the client turns that into a sadr::Error.
///
/// Security and limits (docs/cli.md, "Security"): a server may require the
/// run's secret (PLAIN) or CURVE with authorized client keys, checked by a ZAP
/// handler before any message is accepted; every socket refuses frames above
/// kMaxFrameBytes (ZMQ_MAXMSGSIZE, which also bounds the security handshake),
/// so a peer without credentials can make a server hold at most one such frame
/// per connection, and at most ServerOptions::max_pending such connections.
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
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sadr/common/status.hpp"
#include "sadr/common/v1/frame.pb.h"
#include "sadr/wire/curve_keys.hpp"

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

/// Largest ZeroMQ frame any sadr socket accepts (ZMQ_MAXMSGSIZE): a peer that
/// declares a larger frame, before or after the security handshake, is
/// disconnected at once. Larger bodies travel as several frames.
inline constexpr std::size_t kMaxFrameBytes = std::size_t{4} << 20;

/// CURVE on a server: its own key pair and the public keys of the clients it
/// accepts (everyone else fails in the ZeroMQ handshake).
struct CurveServerKeys {
  CurveKeyPair keys;
  std::vector<std::string> authorized_clients;
};

struct ServerOptions {
  std::string endpoint = "tcp://127.0.0.1:*";  ///< where to bind
  common::v1::ServiceKind kind = common::v1::SERVICE_KIND_UNSPECIFIED;
  /// Larger messages (all body frames together) are refused with an error
  /// reply; clients learn the limit in the handshake and refuse to send them.
  std::int64_t max_message_bytes = std::int64_t{1} << 31;
  std::chrono::milliseconds poll_interval{100};  ///< how often serve() checks the stop flag
  /// Non-empty: only clients presenting this secret connect (ZeroMQ PLAIN
  /// checked by a ZAP handler in this process); others fail in the ZeroMQ
  /// handshake and never reach serve(). Services launched by sadr get a
  /// per-run secret through SADR_RUN_SECRET (service_main.hpp).
  std::string secret;
  /// CURVE instead of a secret (services started by hand on tcp; sadr keygen).
  std::optional<CurveServerKeys> curve;
  std::size_t max_peers = 256;   ///< handshaken peers remembered (LRU beyond)
  std::size_t max_pending = 32;  ///< connections not yet past the security handshake
};

/// What a client presents: the run's secret (PLAIN), or CURVE with its own
/// key pair and the server's public key.
struct ClientCredentials {
  std::string secret;
  CurveKeyPair keys;
  std::string server_public_key;
};

/// Clients of `endpoint` created from now on present `credentials`; empty
/// credentials forget the endpoint. sadr sets a secret for the services it
/// launches and CURVE keys for --fluid/--ssa with --key/--server-key.
void set_client_credentials(const std::string& endpoint, const ClientCredentials& credentials);
/// set_client_credentials with a secret only.
void set_client_secret(const std::string& endpoint, const std::string& secret);
/// True for ipc://, inproc:// and tcp on 127.0.0.0/8, [::1] or localhost: the
/// endpoints that need no CURVE keys (and get no warning without them).
bool is_local_endpoint(const std::string& endpoint);
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
  /// Handshaken peers and pending connections remembered, after reading the
  /// connection events that arrived so far. Not while serve() runs.
  [[nodiscard]] std::size_t peer_count();
  [[nodiscard]] std::size_t pending_count();

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
  /// Every call throws kUnavailable at once (not after the timeout) when the
  /// ZeroMQ security handshake fails (no or wrong secret or key) or the
  /// server closes the connection while a reply is pending.
  common::v1::HandshakeReply handshake(common::v1::ServiceKind expected,
                                       std::uint32_t protocol_version);
  /// Sends `request`, waits for a reply of the type of `reply` and parses it.
  /// Throws sadr::Error on timeout, framing errors or an unparsable reply, and
  /// kInvalidArgument without sending when the request is above the server's
  /// message limit (learnt in the handshake).
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
  std::uint64_t server_limit_ = 0;  ///< the server's max_message_bytes (0: unknown)
  std::function<void()> liveness_;
};

}  // namespace sadr::wire
