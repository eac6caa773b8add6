// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/service_clients.hpp"

#include "sadr/common/version.hpp"
#include "sadr/wire/convert.hpp"

namespace sadr::orchestrator {
namespace {

/// Throws sadr::Error prefixed with the service name unless `status` is OK.
void check(const common::v1::Status& status, const char* service, const char* what) {
  const Status s = wire::from_proto(status);
  if (!s.ok()) throw Error(s.code, std::string(service) + " " + what + ": " + s.message, s.details);
}

}  // namespace

// ---------------------------------------------------------------- fluid

FluidClient::FluidClient(const std::string& endpoint, std::chrono::milliseconds timeout)
    : rpc_(endpoint, "fluid_service", timeout) {
  hello_ = rpc_.handshake(common::v1::SERVICE_KIND_FLUID, kProtocolVersion);
}

fluid::v1::FluidReply FluidClient::call(const fluid::v1::FluidRequest& request) {
  fluid::v1::FluidReply reply;
  rpc_.call(request, reply);
  check(reply.status(), "fluid_service", "failed");
  return reply;
}

fluid::v1::InitReply FluidClient::init(const fluid::v1::InitRequest& request) {
  fluid::v1::FluidRequest r;
  *r.mutable_init() = request;
  return call(r).init();
}

fluid::v1::AdvanceReply FluidClient::advance(const fluid::v1::AdvanceRequest& request) {
  fluid::v1::FluidRequest r;
  *r.mutable_advance() = request;
  return call(r).advance();
}

fluid::v1::GetStateReply FluidClient::get_state(const fluid::v1::GetStateRequest& request) {
  fluid::v1::FluidRequest r;
  *r.mutable_get_state() = request;
  return call(r).get_state();
}

void FluidClient::set_species(const fluid::v1::SetSpeciesRequest& request) {
  fluid::v1::FluidRequest r;
  *r.mutable_set_species() = request;
  call(r);
}

common::v1::Snapshot FluidClient::snapshot(std::uint64_t step_index) {
  fluid::v1::FluidRequest r;
  r.mutable_snapshot()->set_step_index(step_index);
  return call(r).snapshot().snapshot();
}

void FluidClient::restore(const common::v1::Snapshot& snapshot) {
  fluid::v1::FluidRequest r;
  *r.mutable_restore()->mutable_snapshot() = snapshot;
  call(r);
}

void FluidClient::shutdown() noexcept {
  try {
    fluid::v1::FluidRequest r;
    r.mutable_shutdown();
    rpc_.set_timeout(std::chrono::seconds(2));
    call(r);
  } catch (...) {
  }
}

// ---------------------------------------------------------------- ssa

SsaClient::SsaClient(const std::string& endpoint, std::chrono::milliseconds timeout)
    : rpc_(endpoint, "ssa_service", timeout) {
  hello_ = rpc_.handshake(common::v1::SERVICE_KIND_SSA, kProtocolVersion);
}

ssa::v1::SsaReply SsaClient::call(const ssa::v1::SsaRequest& request) {
  ssa::v1::SsaReply reply;
  rpc_.call(request, reply);
  check(reply.status(), "ssa_service", "failed");
  return reply;
}

ssa::v1::InitReply SsaClient::init(const ssa::v1::InitRequest& request) {
  ssa::v1::SsaRequest r;
  *r.mutable_init() = request;
  return call(r).init();
}

ssa::v1::AdvanceReply SsaClient::advance(const ssa::v1::AdvanceRequest& request) {
  ssa::v1::SsaRequest r;
  *r.mutable_advance() = request;
  return call(r).advance();
}

ssa::v1::GetCountsReply SsaClient::get_counts(const ssa::v1::GetCountsRequest& request) {
  ssa::v1::SsaRequest r;
  *r.mutable_get_counts() = request;
  return call(r).get_counts();
}

common::v1::Snapshot SsaClient::snapshot(std::uint64_t step_index) {
  ssa::v1::SsaRequest r;
  r.mutable_snapshot()->set_step_index(step_index);
  return call(r).snapshot().snapshot();
}

void SsaClient::restore(const common::v1::Snapshot& snapshot) {
  ssa::v1::SsaRequest r;
  *r.mutable_restore()->mutable_snapshot() = snapshot;
  call(r);
}

void SsaClient::shutdown() noexcept {
  try {
    ssa::v1::SsaRequest r;
    r.mutable_shutdown();
    rpc_.set_timeout(std::chrono::seconds(2));
    call(r);
  } catch (...) {
  }
}

}  // namespace sadr::orchestrator
