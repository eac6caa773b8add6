// SPDX-License-Identifier: MIT
#include "sadr/wire/rpc.hpp"

#include <unistd.h>
#include <algorithm>
#include <cerrno>
#include <future>
#include <map>
#include <mutex>
#include <set>
#include <thread>
#include <vector>
#include <zmq.hpp>
#include <zmq_addon.hpp>

#include "sadr/common/log.hpp"
#include "sadr/common/v1/status.pb.h"
#include "sadr/common/version.hpp"
#include "sadr/wire/convert.hpp"

namespace sadr::wire {
namespace {

constexpr std::string_view kHandshakeType = "sadr.common.v1.HandshakeRequest";
constexpr std::string_view kHandshakeReplyType = "sadr.common.v1.HandshakeReply";
constexpr std::string_view kStatusType = "sadr.common.v1.Status";

/// One context per process, never destroyed: inproc endpoints need a shared
/// context, and a context torn down at exit would block on sockets that
/// detached threads still hold.
zmq::context_t& shared_context() {
  static auto* ctx = new zmq::context_t(1);
  return *ctx;
}

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

/// A ZeroMQ message that takes ownership of `bytes` instead of copying them
/// (the coupling loop sends ~40 bytes per particle each step: copies add up).
zmq::message_t adopt(std::string bytes) {
  if (bytes.empty()) return zmq::message_t();
  auto* owned = new std::string(std::move(bytes));
  return zmq::message_t(
      owned->data(), owned->size(),
      [](void*, void* hint) { delete static_cast<std::string*>(hint); }, owned);
}

std::string_view view(const zmq::message_t& m) {
  return {static_cast<const char*>(m.data()), m.size()};
}

// ---- authentication (ZAP, RFC 27): one handler per process ------------------

std::mutex g_auth_mutex;
std::map<std::string, std::string> g_domain_secrets;    // server ZAP domain -> secret
std::map<std::string, std::string> g_endpoint_secrets;  // client endpoint -> secret

bool same_secret(std::string_view a, std::string_view b) {
  unsigned diff = a.size() == b.size() ? 0u : 1u;  // constant time in the content
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) {
    diff |= static_cast<unsigned char>(a[i]) ^ static_cast<unsigned char>(b[i]);
  }
  return diff == 0;
}

/// Answers ZAP requests [version, id, domain, address, identity, mechanism,
/// credentials...]: our domains accept PLAIN with the domain's secret only;
/// domains of other sockets are accepted (they did not ask for a secret).
void zap_loop(std::promise<void>* bound) {
  zmq::socket_t zap(shared_context(), zmq::socket_type::rep);
  zap.bind("inproc://zeromq.zap.01");
  bound->set_value();
  for (;;) {
    std::vector<zmq::message_t> req;
    try {
      if (!zmq::recv_multipart(zap, std::back_inserter(req))) continue;
    } catch (const zmq::error_t&) {
      continue;
    }
    std::string status = "400", text = "no or wrong run secret";
    if (req.size() >= 6) {
      std::lock_guard lock(g_auth_mutex);
      const auto it = g_domain_secrets.find(req[2].to_string());
      if (it == g_domain_secrets.end() || (req[5].to_string() == "PLAIN" && req.size() >= 8 &&
                                           same_secret(view(req[7]), it->second))) {
        status = "200";
        text = "OK";
      }
    }
    if (status != "200") log::warn("refused a connection without the run's secret");
    std::vector<zmq::message_t> out;
    out.emplace_back(std::string_view("1.0"));
    if (req.size() > 1) {
      out.emplace_back(req[1].data(), req[1].size());
    } else {
      out.emplace_back();
    }
    out.emplace_back(std::string_view(status));
    out.emplace_back(std::string_view(text));
    out.emplace_back(std::string_view("sadr"));
    out.emplace_back();
    zmq::send_multipart(zap, out);
  }
}

void ensure_zap_handler() {
  static std::once_flag once;
  std::call_once(once, [] {
    std::promise<void> bound;
    std::thread(zap_loop, &bound).detach();
    bound.get_future().wait();
  });
}

/// Number of frames up to and including the empty delimiter (or all frames if none).
std::size_t envelope_size(const std::vector<zmq::message_t>& frames) {
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (frames[i].size() == 0) return i + 1;
  }
  return frames.size();
}

}  // namespace

void set_client_secret(const std::string& endpoint, const std::string& secret) {
  std::lock_guard lock(g_auth_mutex);
  if (secret.empty()) {
    g_endpoint_secrets.erase(endpoint);
  } else {
    g_endpoint_secrets[endpoint] = secret;
  }
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
  zmq::socket_t socket{shared_context(), zmq::socket_type::router};
  std::set<std::string> handshaken;  // ROUTER identities that completed a handshake
  std::string zap_domain;            // registered in g_domain_secrets when a secret is set

  /// Returns the reply [header, body] for one request.
  std::pair<std::string, std::string> dispatch(const std::string& peer,
                                               const std::vector<zmq::message_t>& frames,
                                               RequestHandler& handler, bool& shutdown);
};

RpcServer::RpcServer(ServerOptions options) : impl_(std::make_unique<Impl>()) {
  impl_->options = std::move(options);
  auto& s = impl_->socket;
  s.set(zmq::sockopt::linger, 0);
  s.set(zmq::sockopt::maxmsgsize, impl_->options.max_message_bytes);
  if (!impl_->options.secret.empty()) {
    ensure_zap_handler();
    static std::atomic<unsigned> counter{0};
    impl_->zap_domain = "sadr-" + std::to_string(getpid()) + "-" + std::to_string(counter++);
    {
      std::lock_guard lock(g_auth_mutex);
      g_domain_secrets[impl_->zap_domain] = impl_->options.secret;
    }
    s.set(zmq::sockopt::zap_domain, impl_->zap_domain);
    s.set(zmq::sockopt::plain_server, 1);
  }
  try {
    s.bind(impl_->options.endpoint);
  } catch (const zmq::error_t& e) {
    throw Error(StatusCode::kUnavailable, std::string(service_name(impl_->options.kind)) +
                                              " cannot bind '" + impl_->options.endpoint +
                                              "': " + e.what());
  }
}

RpcServer::~RpcServer() {
  if (impl_ && !impl_->zap_domain.empty()) {
    std::lock_guard lock(g_auth_mutex);
    g_domain_secrets.erase(impl_->zap_domain);
  }
}

std::string RpcServer::endpoint() const {
  return impl_->socket.get(zmq::sockopt::last_endpoint);
}

std::pair<std::string, std::string> RpcServer::Impl::dispatch(
    const std::string& peer, const std::vector<zmq::message_t>& frames, RequestHandler& handler,
    bool& shutdown) {
  const std::string me(service_name(options.kind));
  auto refuse = [&](StatusCode code, const std::string& why) {
    log::warn("refused a request: ", why);
    return std::pair{make_header(kStatusType, 0), status_body(code, why)};
  };
  // frames: [envelope...][empty delimiter][header][body]; the envelope is the
  // ROUTER identity plus, for REQ clients with req_correlate, a request id.
  const std::size_t payload = envelope_size(frames);
  if (frames.size() - payload != 2) {
    return refuse(StatusCode::kProtocolMismatch,
                  "malformed message: expected 2 frames [FrameHeader][body], got " +
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
  const std::string_view body = view(frames[payload + 1]);  // parsed in place, not copied
  if (header.message_type() == kHandshakeType) {
    common::v1::HandshakeRequest req;
    common::v1::HandshakeReply rep;
    rep.set_protocol_version(kProtocolVersion);
    rep.set_kind(options.kind);
    rep.set_server_version(kVersion);
    rep.set_pid(static_cast<std::uint32_t>(getpid()));
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
      handshaken.insert(peer);
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
  if (!handshaken.count(peer)) {
    return refuse(StatusCode::kFailedPrecondition,
                  "no handshake: send a sadr.common.v1.HandshakeRequest before " +
                      std::string(handler.request_type()));
  }
  std::string reply = handler.handle(body, shutdown);
  return {make_header(handler.reply_type(), header.sequence()), std::move(reply)};
}

void RpcServer::serve(RequestHandler& handler, const std::atomic<bool>* stop) {
  auto& s = impl_->socket;
  bool shutdown = false;
  while (!shutdown && !(stop && stop->load())) {
    zmq::pollitem_t items[] = {{s.handle(), 0, ZMQ_POLLIN, 0}};
    try {
      zmq::poll(items, 1, impl_->options.poll_interval);
    } catch (const zmq::error_t& e) {
      if (e.num() == EINTR) continue;  // a signal: re-check the stop flag
      throw;
    }
    if (!(items[0].revents & ZMQ_POLLIN)) continue;
    std::vector<zmq::message_t> frames;
    try {
      if (!zmq::recv_multipart(s, std::back_inserter(frames), zmq::recv_flags::dontwait)) continue;
    } catch (const zmq::error_t& e) {
      if (e.num() == EINTR || e.num() == EAGAIN) continue;
      throw;
    }
    const std::size_t env = envelope_size(frames);
    if (env < 2) continue;  // no identity + delimiter: not from a REQ/DEALER peer
    const std::string peer = frames[0].to_string();
    auto [header, body] = impl_->dispatch(peer, frames, handler, shutdown);
    std::vector<zmq::message_t> out;
    for (std::size_t i = 0; i < env; ++i) out.emplace_back(frames[i].data(), frames[i].size());
    out.emplace_back(header.data(), header.size());
    out.push_back(adopt(std::move(body)));
    zmq::send_multipart(s, out);
  }
}

// ---------------------------------------------------------------- client

struct RpcClient::Impl {
  zmq::socket_t socket{shared_context(), zmq::socket_type::req};
  std::vector<zmq::message_t> reply;  ///< the last reply's [header][body] frames
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
  {
    std::lock_guard lock(g_auth_mutex);
    if (const auto it = g_endpoint_secrets.find(endpoint_); it != g_endpoint_secrets.end()) {
      s.set(zmq::sockopt::plain_username, "sadr");
      s.set(zmq::sockopt::plain_password, it->second);
    }
  }
  try {
    s.connect(endpoint_);
  } catch (const zmq::error_t& e) {
    throw Error(StatusCode::kUnavailable,
                "cannot connect to " + peer_name_ + " at '" + endpoint_ + "': " + e.what());
  }
}

RpcClient::~RpcClient() = default;

void RpcClient::exchange(std::string header, std::string body) {
  auto& s = impl_->socket;
  s.send(zmq::buffer(header), zmq::send_flags::sndmore);
  s.send(adopt(std::move(body)), zmq::send_flags::none);
  zmq::pollitem_t items[] = {{s.handle(), 0, ZMQ_POLLIN, 0}};
  const auto deadline = std::chrono::steady_clock::now() + timeout_;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      throw Error(StatusCode::kDeadlineExceeded,
                  peer_name_ + " at " + endpoint_ + " did not answer within " +
                      std::to_string(timeout_.count()) + " ms (is it running?)");
    }
    try {
      zmq::poll(items, 1, std::min(left, std::chrono::milliseconds(200)));
    } catch (const zmq::error_t& e) {
      if (e.num() == EINTR) continue;
      throw;
    }
    if (items[0].revents & ZMQ_POLLIN) break;
    if (liveness_) liveness_();
  }
  auto& frames = impl_->reply;
  frames.clear();
  (void)zmq::recv_multipart(s, std::back_inserter(frames));
  if (frames.size() != 2) {
    throw Error(StatusCode::kProtocolMismatch, peer_name_ + " sent a reply with " +
                                                   std::to_string(frames.size()) +
                                                   " frames, expected 2 [FrameHeader][body]");
  }
}

void RpcClient::call_raw(const std::string& header, const std::string& body,
                         std::string& reply_header, std::string& reply_body) {
  exchange(header, body);
  reply_header = impl_->reply[0].to_string();
  reply_body = impl_->reply[1].to_string();
}

void RpcClient::call(const google::protobuf::Message& request, google::protobuf::Message& reply) {
  exchange(make_header(request.GetTypeName(), ++sequence_), to_bytes(request));
  const std::string_view rh = view(impl_->reply[0]);
  const std::string_view rb = view(impl_->reply[1]);  // parsed in place, not copied
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
  return rep;
}

}  // namespace sadr::wire
