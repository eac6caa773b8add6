// SPDX-License-Identifier: MIT
#include "sadr/wire/rpc.hpp"

#include <unistd.h>
#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstdio>
#include <memory>
#include <thread>
#include <vector>
#include <zmq.hpp>
#include <zmq_addon.hpp>

#include "auth.hpp"
#include "peer_table.hpp"
#include "sadr/common/log.hpp"
#include "sadr/common/v1/status.pb.h"
#include "sadr/common/version.hpp"
#include "sadr/wire/convert.hpp"
#include "zmq_support.hpp"

namespace sadr::wire {
namespace {

using detail::view;

constexpr std::string_view kHandshakeType = "sadr.common.v1.HandshakeRequest";
constexpr std::string_view kHandshakeReplyType = "sadr.common.v1.HandshakeReply";
constexpr std::string_view kStatusType = "sadr.common.v1.Status";

std::string to_bytes(const google::protobuf::Message& m) {
  std::string out;
  m.SerializeToString(&out);
  return out;
}

std::string make_header(std::string_view type, std::uint64_t sequence) {
  common::v1::FrameHeader h;
  h.set_protocol_version(kProtocolVersion);
  h.set_message_type(std::string(type));
  h.set_sequence(sequence);
  return to_bytes(h);
}

std::string status_body(StatusCode code, const std::string& message) {
  common::v1::Status s;
  to_proto(Status{code, message, {}}, s);
  return to_bytes(s);
}

/// Appends `body` as frames of at most kMaxFrameBytes that share ownership of
/// the bytes instead of copying them (the coupling loop sends ~40 bytes per
/// particle each step: copies add up). An empty body is one empty frame.
void append_body(std::vector<zmq::message_t>& out, std::string body) {
  if (body.empty()) {
    out.emplace_back();
    return;
  }
  auto owned = std::make_shared<const std::string>(std::move(body));
  for (std::size_t at = 0; at < owned->size(); at += kMaxFrameBytes) {
    const std::size_t n = std::min(kMaxFrameBytes, owned->size() - at);
    auto* hold = new std::shared_ptr<const std::string>(owned);
    out.emplace_back(
        const_cast<char*>(owned->data() + at), n,
        [](void*, void* hint) { delete static_cast<std::shared_ptr<const std::string>*>(hint); },
        hold);
  }
}

/// The body of a received message, frames[first..]: a view of the frame when
/// there is one, else the frames joined into `joined`.
std::string_view body_of(const std::vector<zmq::message_t>& frames, std::size_t first,
                         std::string& joined) {
  if (frames.size() == first + 1) return view(frames[first]);
  joined.clear();
  for (std::size_t i = first; i < frames.size(); ++i) joined.append(view(frames[i]));
  return joined;
}

std::size_t body_size(const std::vector<zmq::message_t>& frames, std::size_t first) {
  std::size_t n = 0;
  for (std::size_t i = first; i < frames.size(); ++i) n += frames[i].size();
  return n;
}

std::string mib(std::uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MiB", static_cast<double>(bytes) / (1024.0 * 1024.0));
  return text;
}

/// Number of frames up to and including the empty delimiter (or all frames if none).
std::size_t envelope_size(const std::vector<zmq::message_t>& frames) {
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (frames[i].size() == 0) return i + 1;
  }
  return frames.size();
}

}  // namespace

bool is_local_endpoint(const std::string& endpoint) {
  if (endpoint.rfind("tcp://", 0) != 0) return true;
  const std::string host = endpoint.substr(6, endpoint.rfind(':') - 6);
  return host == "localhost" || host == "[::1]" || host == "::1" || host.rfind("127.", 0) == 0;
}

std::string shorten(std::string_view text, std::size_t limit) {
  if (text.size() <= limit) return std::string(text);
  return std::string(text.substr(0, limit)) + "... (" + std::to_string(text.size()) + " bytes)";
}

std::string_view service_name(common::v1::ServiceKind kind) {
  switch (kind) {
    case common::v1::SERVICE_KIND_FLUID:
      return "fluid_service";
    case common::v1::SERVICE_KIND_SSA:
      return "ssa_service";
    default:
      return "unspecified service";
  }
}

// ---------------------------------------------------------------- server

struct RpcServer::Impl {
  ServerOptions options;
  zmq::socket_t socket{detail::shared_context(), zmq::socket_type::router};
  zmq::socket_t monitor;  // ACCEPTED / DISCONNECTED / CLOSED of `socket`
  detail::PeerTable peers{256, 32};
  std::string zap_domain;     // registered with the ZAP handler when a secret or CURVE is set
  std::size_t cut_total = 0;  // pending connections closed over the limit

  void drain_events() {
    detail::MonitorEvent e;
    while (detail::next_event(monitor, e)) peers.on_event(e);
    const std::size_t before = cut_total;
    cut_total += peers.enforce_pending_limit();
    // Logged when the total reaches 1, 2, 4, 8, ...: a flood of connections
    // must not become a flood of log lines.
    if (cut_total > before && std::bit_floor(cut_total) > before) {
      log::warn("closed connections still in the security handshake (more than ",
                options.max_pending, " at once; ", cut_total, " so far)");
    }
  }

  /// Returns the reply [header, body] for one request.
  std::pair<std::string, std::string> dispatch(const std::string& peer, int fd,
                                               const std::vector<zmq::message_t>& frames,
                                               RequestHandler& handler, bool& shutdown);
};

RpcServer::RpcServer(ServerOptions options) : impl_(std::make_unique<Impl>()) {
  impl_->options = std::move(options);
  impl_->peers = detail::PeerTable(impl_->options.max_peers, impl_->options.max_pending);
  auto& s = impl_->socket;
  s.set(zmq::sockopt::linger, 0);
  s.set(zmq::sockopt::maxmsgsize, static_cast<std::int64_t>(kMaxFrameBytes));
  s.set(zmq::sockopt::handshake_ivl, 10000);  // a security handshake may take 10 s at most
  impl_->zap_domain = detail::secure_server(s, impl_->options);
  impl_->monitor =
      detail::monitor_socket(s, ZMQ_EVENT_ACCEPTED | ZMQ_EVENT_DISCONNECTED | ZMQ_EVENT_CLOSED);
  try {
    s.bind(impl_->options.endpoint);
  } catch (const zmq::error_t& e) {
    detail::release_domain(impl_->zap_domain);
    throw Error(StatusCode::kUnavailable, std::string(service_name(impl_->options.kind)) +
                                              " cannot bind '" + impl_->options.endpoint +
                                              "': " + e.what());
  }
}

RpcServer::~RpcServer() {
  if (!impl_) return;
  detail::stop_monitor(impl_->socket);
  detail::release_domain(impl_->zap_domain);
}

std::string RpcServer::endpoint() const {
  return impl_->socket.get(zmq::sockopt::last_endpoint);
}

std::size_t RpcServer::peer_count() {
  impl_->drain_events();
  return impl_->peers.peers();
}

std::size_t RpcServer::pending_count() {
  impl_->drain_events();
  return impl_->peers.pending();
}

std::pair<std::string, std::string> RpcServer::Impl::dispatch(
    const std::string& peer, int fd, const std::vector<zmq::message_t>& frames,
    RequestHandler& handler, bool& shutdown) {
  const std::string me(service_name(options.kind));
  auto refuse = [&](StatusCode code, const std::string& why) {
    log::warn("refused a request: ", why);
    return std::pair{make_header(kStatusType, 0), status_body(code, why)};
  };
  // frames: [envelope...][empty delimiter][header][body...]; the envelope is
  // the ROUTER identity plus, for REQ clients with req_correlate, a request id.
  const std::size_t payload = envelope_size(frames);
  if (frames.size() - payload < 2) {
    return refuse(StatusCode::kProtocolMismatch,
                  "malformed message: expected [FrameHeader][body] (2 or more frames), got " +
                      std::to_string(frames.size() - payload));
  }
  common::v1::FrameHeader header;
  if (!header.ParseFromArray(frames[payload].data(), static_cast<int>(frames[payload].size()))) {
    return refuse(StatusCode::kProtocolMismatch,
                  "malformed frame header (" + std::to_string(frames[payload].size()) +
                      " bytes): expected a serialized sadr.common.v1.FrameHeader");
  }
  if (header.protocol_version() != kProtocolVersion) {
    return refuse(StatusCode::kProtocolMismatch,
                  "protocol version mismatch: this " + me + " speaks sadr wire protocol v" +
                      std::to_string(kProtocolVersion) + ", the request declared v" +
                      std::to_string(header.protocol_version()) + " (message " +
                      shorten(header.message_type()) + ")");
  }
  const std::size_t bytes = body_size(frames, payload + 1);
  if (bytes > static_cast<std::uint64_t>(options.max_message_bytes)) {
    return refuse(StatusCode::kInvalidArgument,
                  "message of " + std::to_string(bytes) + " bytes (" + mib(bytes) +
                      ") is above this " + me + "'s limit of " +
                      mib(static_cast<std::uint64_t>(options.max_message_bytes)) +
                      " (--max-message-mb)");
  }
  std::string joined;
  const std::string_view body = body_of(frames, payload + 1, joined);  // parsed in place
  if (header.message_type() == kHandshakeType) {
    common::v1::HandshakeRequest req;
    common::v1::HandshakeReply rep;
    rep.set_protocol_version(kProtocolVersion);
    rep.set_kind(options.kind);
    rep.set_server_version(kVersion);
    rep.set_pid(static_cast<std::uint32_t>(getpid()));
    rep.set_max_message_bytes(static_cast<std::uint64_t>(options.max_message_bytes));
    Status st;
    if (!req.ParseFromArray(body.data(), static_cast<int>(body.size()))) {
      st = {StatusCode::kInvalidArgument,
            "malformed handshake: the body is not a sadr.common.v1.HandshakeRequest (" +
                std::to_string(body.size()) + " bytes)",
            {}};
    } else if (req.protocol_version() != kProtocolVersion) {
      st = {StatusCode::kProtocolMismatch,
            "protocol version mismatch: this " + me + " speaks sadr wire protocol v" +
                std::to_string(kProtocolVersion) + ", the client asked for v" +
                std::to_string(req.protocol_version()),
            {{"expected", std::to_string(kProtocolVersion)},
             {"received", std::to_string(req.protocol_version())}}};
    } else if (req.expected_kind() != common::v1::SERVICE_KIND_UNSPECIFIED &&
               req.expected_kind() != options.kind) {
      st = {StatusCode::kProtocolMismatch,
            "wrong service: this endpoint is " + me + ", the client expected " +
                std::string(service_name(req.expected_kind())),
            {}};
    } else {
      peers.mark_handshaken(peer, fd);
      log::info("handshake from '", shorten(req.client_name()), "' accepted (protocol v",
                kProtocolVersion, ")");
    }
    if (!st.ok()) log::warn("handshake refused: ", st.message);
    to_proto(st, *rep.mutable_status());
    return {make_header(kHandshakeReplyType, header.sequence()), to_bytes(rep)};
  }
  if (header.message_type() != handler.request_type()) {
    return refuse(StatusCode::kProtocolMismatch,
                  "unexpected message type '" + shorten(header.message_type()) + "': this " + me +
                      " accepts " + std::string(kHandshakeType) + " and " +
                      std::string(handler.request_type()));
  }
  if (!peers.handshaken(peer, fd)) {
    return refuse(StatusCode::kFailedPrecondition,
                  "no handshake: send a sadr.common.v1.HandshakeRequest before " +
                      std::string(handler.request_type()) +
                      " (on every new connection, even with a routing id used before)");
  }
  std::string reply = handler.handle(body, shutdown);
  return {make_header(handler.reply_type(), header.sequence()), std::move(reply)};
}

void RpcServer::serve(RequestHandler& handler, const std::atomic<bool>* stop) {
  auto& s = impl_->socket;
  bool shutdown = false;
  while (!shutdown && !(stop && stop->load())) {
    zmq::pollitem_t items[] = {{s.handle(), 0, ZMQ_POLLIN, 0},
                               {impl_->monitor.handle(), 0, ZMQ_POLLIN, 0}};
    try {
      zmq::poll(items, 2, impl_->options.poll_interval);
    } catch (const zmq::error_t& e) {
      if (e.num() == EINTR) continue;  // a signal: re-check the stop flag
      throw;
    }
    // Connection events first: a DISCONNECTED that happened before this
    // message arrived is already queued, so a reused fd is never mistaken
    // for the old connection.
    impl_->drain_events();
    if (!(items[0].revents & ZMQ_POLLIN)) continue;
    std::vector<zmq::message_t> frames;
    try {
      if (!zmq::recv_multipart(s, std::back_inserter(frames), zmq::recv_flags::dontwait)) continue;
    } catch (const zmq::error_t& e) {
      if (e.num() == EINTR || e.num() == EAGAIN) continue;
      throw;
    }
    impl_->drain_events();
    const std::size_t env = envelope_size(frames);
    if (env < 2) continue;  // no identity + delimiter: not from a REQ/DEALER peer
    const int fd = zmq_msg_get(frames.back().handle(), ZMQ_SRCFD);  // -1 over inproc
    if (fd >= 0) impl_->peers.saw_message(fd);
    const std::string peer = frames[0].to_string();
    auto [header, body] = impl_->dispatch(peer, fd, frames, handler, shutdown);
    std::vector<zmq::message_t> out;
    for (std::size_t i = 0; i < env; ++i) out.emplace_back(frames[i].data(), frames[i].size());
    out.emplace_back(header.data(), header.size());
    append_body(out, std::move(body));
    zmq::send_multipart(s, out);
  }
}

// ---------------------------------------------------------------- client

struct RpcClient::Impl {
  zmq::socket_t socket{detail::shared_context(), zmq::socket_type::req};
  zmq::socket_t monitor;              // security handshake results and disconnects of `socket`
  std::string mechanism;              // NULL, PLAIN or CURVE
  std::string refused;                // why the last security handshake failed ("" if it did not)
  std::vector<zmq::message_t> reply;  ///< the last reply's [header][body...] frames
  std::string joined;                 ///< the reply body when it came in several frames

  /// Reads pending monitor events; returns true if one was a disconnect.
  bool drain_events() {
    bool disconnected = false;
    detail::MonitorEvent e;
    while (detail::next_event(monitor, e)) {
      switch (e.event) {
        case ZMQ_EVENT_HANDSHAKE_SUCCEEDED:
          refused.clear();
          break;
        case ZMQ_EVENT_HANDSHAKE_FAILED_AUTH:
          refused = "it refused our credentials (" + mechanism + ", ZAP status " +
                    std::to_string(e.value) + "): a wrong or missing run secret or CURVE key";
          break;
        case ZMQ_EVENT_HANDSHAKE_FAILED_PROTOCOL:
        case ZMQ_EVENT_HANDSHAKE_FAILED_NO_DETAIL:
          refused = "the ZeroMQ security handshake failed (we offered " + mechanism +
                    "): it expects another mechanism or key (run secret, or CURVE with "
                    "--key and --server-key)";
          break;
        case ZMQ_EVENT_DISCONNECTED:
          disconnected = true;
          break;
        default:
          break;
      }
    }
    return disconnected;
  }
};

RpcClient::RpcClient(std::string endpoint, std::string peer_name, std::chrono::milliseconds timeout)
    : impl_(std::make_unique<Impl>()),
      endpoint_(std::move(endpoint)),
      peer_name_(std::move(peer_name)),
      timeout_(timeout) {
  auto& s = impl_->socket;
  s.set(zmq::sockopt::linger, 0);
  s.set(zmq::sockopt::req_relaxed, 1);    // may resend after a timeout
  s.set(zmq::sockopt::req_correlate, 1);  // ... and ignore the late reply
  s.set(zmq::sockopt::maxmsgsize, static_cast<std::int64_t>(kMaxFrameBytes));
  impl_->mechanism = detail::secure_client(s, endpoint_);
  impl_->monitor =
      detail::monitor_socket(s,
                             ZMQ_EVENT_HANDSHAKE_SUCCEEDED | ZMQ_EVENT_HANDSHAKE_FAILED_AUTH |
                                 ZMQ_EVENT_HANDSHAKE_FAILED_PROTOCOL |
                                 ZMQ_EVENT_HANDSHAKE_FAILED_NO_DETAIL | ZMQ_EVENT_DISCONNECTED,
                             /*unbounded=*/true);
  try {
    s.connect(endpoint_);
  } catch (const zmq::error_t& e) {
    throw Error(StatusCode::kUnavailable,
                "cannot connect to " + peer_name_ + " at '" + endpoint_ + "': " + e.what());
  }
}

RpcClient::~RpcClient() {
  detail::stop_monitor(impl_->socket);
}

void RpcClient::exchange(std::string header, std::string body) {
  auto& s = impl_->socket;
  (void)impl_->drain_events();  // a disconnect before this request does not concern it
  const auto deadline = std::chrono::steady_clock::now() + timeout_;
  auto fail = [&](const std::string& why) {
    throw Error(StatusCode::kUnavailable, peer_name_ + " at " + endpoint_ + ": " + why);
  };
  auto time_left = [&](const char* what) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      throw Error(StatusCode::kDeadlineExceeded,
                  peer_name_ + " at " + endpoint_ + " did not " + what + " within " +
                      std::to_string(timeout_.count()) + " ms (is it running?)");
    }
    return std::min(left, std::chrono::milliseconds(200));
  };
  // libzmq (4.3.4) does not reconnect after the peer refused the security
  // handshake: the REQ socket then has no pipe, and a blocking send would
  // wait forever. So a known refusal fails before sending, and the send is
  // non-blocking, retried until the deadline while the monitor is watched.
  if (!impl_->refused.empty()) fail(impl_->refused);
  std::vector<zmq::message_t> out;
  out.emplace_back(header.data(), header.size());
  append_body(out, std::move(body));
  zmq::pollitem_t items[] = {{s.handle(), 0, ZMQ_POLLIN, 0},
                             {impl_->monitor.handle(), 0, ZMQ_POLLIN, 0}};
  for (;;) {
    try {
      if (zmq::send_multipart(s, out, zmq::send_flags::dontwait)) break;
    } catch (const zmq::error_t& e) {
      if (e.num() != EINTR) throw;
    }
    items[0].events = ZMQ_POLLOUT;
    try {
      zmq::poll(items, 2, time_left("accept the request"));
    } catch (const zmq::error_t& e) {
      if (e.num() != EINTR) throw;
    }
    (void)impl_->drain_events();  // nothing was sent yet: a disconnect loses no request
    if (!impl_->refused.empty()) fail(impl_->refused);
    if (liveness_) liveness_();
  }
  items[0].events = ZMQ_POLLIN;
  for (;;) {
    if (!impl_->refused.empty()) fail(impl_->refused);
    const auto wait = time_left("answer");
    try {
      zmq::poll(items, 2, wait);
    } catch (const zmq::error_t& e) {
      if (e.num() == EINTR) continue;
      throw;
    }
    if (items[0].revents & ZMQ_POLLIN) break;
    if (impl_->drain_events() && impl_->refused.empty()) {
      // The request died with the connection (REQ does not resend it). If the
      // process is gone, the liveness check says so by name; give it a moment.
      for (int i = 0; i < 10 && liveness_; ++i) {
        liveness_();
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
      }
      fail(
          "it closed the connection while this request was pending (it stopped, or it "
          "refused a frame above its limit of " +
          mib(kMaxFrameBytes) + ")");
    }
    if (liveness_) liveness_();
  }
  auto& frames = impl_->reply;
  frames.clear();
  (void)zmq::recv_multipart(s, std::back_inserter(frames));
  if (frames.size() < 2) {
    throw Error(StatusCode::kProtocolMismatch, peer_name_ + " sent a reply with " +
                                                   std::to_string(frames.size()) +
                                                   " frames, expected [FrameHeader][body...]");
  }
}

void RpcClient::call_raw(const std::string& header, const std::string& body,
                         std::string& reply_header, std::string& reply_body) {
  exchange(header, body);
  reply_header = impl_->reply[0].to_string();
  reply_body = std::string(body_of(impl_->reply, 1, impl_->joined));
}

void RpcClient::call(const google::protobuf::Message& request, google::protobuf::Message& reply) {
  std::string body = to_bytes(request);
  if (server_limit_ > 0 && body.size() > server_limit_) {
    throw Error(StatusCode::kInvalidArgument,
                "the " + request.GetTypeName() + " of " + std::to_string(body.size()) + " bytes (" +
                    mib(body.size()) + ") is above the limit of " + peer_name_ + " at " +
                    endpoint_ + ", " + mib(server_limit_) + " (its --max-message-mb); not sent");
  }
  exchange(make_header(request.GetTypeName(), ++sequence_), std::move(body));
  const std::string_view rh = view(impl_->reply[0]);
  const std::string_view rb = body_of(impl_->reply, 1, impl_->joined);  // parsed in place
  common::v1::FrameHeader header;
  if (!header.ParseFromArray(rh.data(), static_cast<int>(rh.size()))) {
    throw Error(StatusCode::kProtocolMismatch,
                peer_name_ + " sent a reply whose header is not a sadr.common.v1.FrameHeader");
  }
  if (header.protocol_version() != kProtocolVersion) {
    throw Error(StatusCode::kProtocolMismatch, peer_name_ + " replied with protocol v" +
                                                   std::to_string(header.protocol_version()) +
                                                   ", this client speaks v" +
                                                   std::to_string(kProtocolVersion));
  }
  if (header.message_type() == kStatusType) {
    common::v1::Status st;
    st.ParseFromArray(rb.data(), static_cast<int>(rb.size()));
    Status s = from_proto(st);
    throw Error(s.code, peer_name_ + " refused the request: " + s.message, s.details);
  }
  if (header.message_type() != reply.GetTypeName()) {
    throw Error(StatusCode::kProtocolMismatch, peer_name_ + " replied with message type '" +
                                                   shorten(header.message_type()) +
                                                   "', expected '" + reply.GetTypeName() + "'");
  }
  if (!reply.ParseFromArray(rb.data(), static_cast<int>(rb.size()))) {
    throw Error(StatusCode::kProtocolMismatch, peer_name_ + " sent an unparsable " +
                                                   reply.GetTypeName() + " (" +
                                                   std::to_string(rb.size()) + " bytes)");
  }
  impl_->reply.clear();
  impl_->joined.clear();
}

common::v1::HandshakeReply RpcClient::handshake(common::v1::ServiceKind expected,
                                                std::uint32_t protocol_version) {
  common::v1::HandshakeRequest req;
  req.set_protocol_version(protocol_version);
  req.set_expected_kind(expected);
  req.set_client_name(std::string("sadr client ") + kVersion);
  common::v1::HandshakeReply rep;
  call(req, rep);
  const Status st = from_proto(rep.status());
  if (!st.ok())
    throw Error(st.code, peer_name_ + " refused the handshake: " + st.message, st.details);
  server_limit_ = rep.max_message_bytes();
  return rep;
}

}  // namespace sadr::wire
