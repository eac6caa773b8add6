// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/service_clients.hpp"

namespace sadr::orchestrator {

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

}  // namespace sadr::orchestrator
