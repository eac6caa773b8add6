// SPDX-License-Identifier: MIT
/// \file service_clients.hpp
/// Typed clients for fluid_service and ssa_service: one method per request,
/// each throwing sadr::Error (with the service named) when the reply's
/// Status is not OK. The orchestrator's coupling loop talks only to these.
#pragma once

#include <chrono>
#include <string>

#include "sadr/fluid/v1/fluid_service.pb.h"
#include "sadr/ssa/v1/ssa_service.pb.h"
#include "sadr/wire/rpc.hpp"

namespace sadr::orchestrator {

class FluidClient {
 public:
  /// Connects and performs the handshake (throws on refusal or timeout).
  FluidClient(const std::string& endpoint, std::chrono::milliseconds timeout);
  fluid::v1::InitReply init(const fluid::v1::InitRequest& request);
  fluid::v1::AdvanceReply advance(const fluid::v1::AdvanceRequest& request);
  fluid::v1::GetStateReply get_state(const fluid::v1::GetStateRequest& request);
  void set_species(const fluid::v1::SetSpeciesRequest& request);
  common::v1::Snapshot snapshot(std::uint64_t step_index);
  void restore(const common::v1::Snapshot& snapshot);
  /// Asks the service to exit; never throws (the service may already be gone).
  void shutdown() noexcept;
  [[nodiscard]] const common::v1::HandshakeReply& hello() const { return hello_; }

 private:
  fluid::v1::FluidReply call(const fluid::v1::FluidRequest& request);
  wire::RpcClient rpc_;
  common::v1::HandshakeReply hello_;
};

class SsaClient {
 public:
  SsaClient(const std::string& endpoint, std::chrono::milliseconds timeout);
  ssa::v1::InitReply init(const ssa::v1::InitRequest& request);
  ssa::v1::AdvanceReply advance(const ssa::v1::AdvanceRequest& request);
  ssa::v1::GetCountsReply get_counts(const ssa::v1::GetCountsRequest& request);
  common::v1::Snapshot snapshot(std::uint64_t step_index);
  void restore(const common::v1::Snapshot& snapshot);
  void shutdown() noexcept;
  [[nodiscard]] const common::v1::HandshakeReply& hello() const { return hello_; }

 private:
  ssa::v1::SsaReply call(const ssa::v1::SsaRequest& request);
  wire::RpcClient rpc_;
  common::v1::HandshakeReply hello_;
};

}  // namespace sadr::orchestrator
