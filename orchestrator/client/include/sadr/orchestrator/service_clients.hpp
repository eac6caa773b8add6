// SPDX-License-Identifier: MIT
/// \file service_clients.hpp
/// Typed clients for fluid_service and ssa_service: one method per request,
/// each throwing sadr::Error (with the service named) when the reply's
/// Status is not OK. The orchestrator's coupling loop talks only to these.
#pragma once

#include <chrono>
#include <functional>
#include <string>

#include "sadr/common/version.hpp"
#include "sadr/fluid/v1/fluid_service.pb.h"
#include "sadr/ssa/v1/ssa_service.pb.h"
#include "sadr/wire/convert.hpp"
#include "sadr/wire/rpc.hpp"

namespace sadr::orchestrator {

/// What both services share: handshake on construction, checked calls,
/// snapshot / restore / shutdown. `Request`/`Reply` are the service's oneof
/// envelope messages.
template <class Request, class Reply>
class ServiceClient {
 public:
  /// Snapshot of the complete service state (opaque blob + metadata).
  common::v1::Snapshot snapshot(std::uint64_t step_index) {
    Request r;
    r.mutable_snapshot()->set_step_index(step_index);
    return call(r).snapshot().snapshot();
  }
  void restore(const common::v1::Snapshot& snapshot) {
    Request r;
    *r.mutable_restore()->mutable_snapshot() = snapshot;
    call(r);
  }
  /// Asks the service to exit; never throws (the service may already be gone).
  void shutdown() noexcept {
    try {
      Request r;
      r.mutable_shutdown();
      rpc_.set_timeout(std::chrono::seconds(2));
      call(r);
    } catch (...) {
    }
  }
  [[nodiscard]] const common::v1::HandshakeReply& hello() const { return hello_; }
  /// See wire::RpcClient::set_liveness_check.
  void set_liveness_check(std::function<void()> check) {
    rpc_.set_liveness_check(std::move(check));
  }

 protected:
  /// Connects and performs the handshake (throws on refusal or timeout).
  ServiceClient(const std::string& endpoint, common::v1::ServiceKind kind,
                std::chrono::milliseconds timeout)
      : rpc_(endpoint, std::string(wire::service_name(kind)), timeout),
        name_(wire::service_name(kind)) {
    hello_ = rpc_.handshake(kind, kProtocolVersion);
  }
  Reply call(const Request& request) {
    Reply reply;
    rpc_.call(request, reply);
    const Status s = wire::from_proto(reply.status());
    if (!s.ok()) throw Error(s.code, name_ + " failed: " + s.message, s.details);
    return reply;
  }

 private:
  wire::RpcClient rpc_;
  std::string name_;
  common::v1::HandshakeReply hello_;
};

class FluidClient : public ServiceClient<fluid::v1::FluidRequest, fluid::v1::FluidReply> {
 public:
  FluidClient(const std::string& endpoint, std::chrono::milliseconds timeout)
      : ServiceClient(endpoint, common::v1::SERVICE_KIND_FLUID, timeout) {}
  fluid::v1::InitReply init(const fluid::v1::InitRequest& request);
  fluid::v1::AdvanceReply advance(const fluid::v1::AdvanceRequest& request);
  fluid::v1::GetStateReply get_state(const fluid::v1::GetStateRequest& request);
  void set_species(const fluid::v1::SetSpeciesRequest& request);
};

class SsaClient : public ServiceClient<ssa::v1::SsaRequest, ssa::v1::SsaReply> {
 public:
  SsaClient(const std::string& endpoint, std::chrono::milliseconds timeout)
      : ServiceClient(endpoint, common::v1::SERVICE_KIND_SSA, timeout) {}
  ssa::v1::InitReply init(const ssa::v1::InitRequest& request);
  ssa::v1::AdvanceReply advance(const ssa::v1::AdvanceRequest& request);
  ssa::v1::GetCountsReply get_counts(const ssa::v1::GetCountsRequest& request);
};

}  // namespace sadr::orchestrator
