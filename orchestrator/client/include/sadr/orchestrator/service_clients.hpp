// SPDX-License-Identifier: MIT
/// \file service_clients.hpp
/// FluidClient and SsaClient: the service interfaces of service_interfaces.hpp
/// over the wire (protocol v1), each call throwing sadr::Error (with the
/// service named) when the reply's Status is not OK. GeometryChannel picks
/// how the per-step geometry travels from the fluid to the SSA.
#pragma once

#include <chrono>
#include <functional>
#include <optional>
#include <string>

#include "sadr/common/version.hpp"
#include "sadr/fluid/v1/fluid_service.pb.h"
#include "sadr/orchestrator/service_interfaces.hpp"
#include "sadr/orchestrator/work_estimate.hpp"
#include "sadr/ssa/v1/ssa_service.pb.h"
#include "sadr/wire/convert.hpp"
#include "sadr/wire/rpc.hpp"
#include "sadr/wire/shared_geometry.hpp"

namespace sadr::orchestrator {

/// The per-step geometry's way from fluid_service to ssa_service: a POSIX
/// shared-memory segment when both run on this host (processes launched here,
/// or --embedded), else inline arrays relayed through the orchestrator.
class GeometryChannel {
 public:
  /// Inline arrays.
  GeometryChannel() = default;
  /// Tries a segment for `particles` particles; falls back to inline arrays
  /// (with a warning naming the system error) if it cannot be created.
  static GeometryChannel on_this_host(std::size_t particles);
  [[nodiscard]] bool shared() const { return shm_.has_value(); }
  /// The segment's name ("" inline).
  [[nodiscard]] const std::string& segment() const;
  /// Both services mapped the segment: drop its name, so nothing is left in
  /// /dev/shm whatever happens next (idempotent; mappings stay valid).
  void release();

 private:
  std::optional<wire::SharedGeometry> shm_;
};

/// What the fluid backend reported after init: its sub-steps ahead at t = 0 (InitReply fields
/// 3-5; all zero from a service before them).
FluidSubsteps fluid_substeps(const fluid::v1::InitReply& reply);

/// The message's bytes with map entries in key order (protobuf's default order
/// of map fields varies between runs).
std::string deterministic_bytes(const google::protobuf::Message& message);

/// What both services share: handshake on construction, checked calls,
/// snapshot / restore / shutdown. `Request`/`Reply` are the service's oneof
/// envelope messages.
template <class Request, class Reply>
class ServiceClient {
 public:
  /// The service's Snapshot message (opaque blob + metadata), serialised
  /// deterministically (map entries in key order): equal states, equal bytes.
  std::string snapshot_bytes(std::uint64_t step_index) {
    Request r;
    r.mutable_snapshot()->set_step_index(step_index);
    return deterministic_bytes(call(r).snapshot().snapshot());
  }
  /// Restores from snapshot_bytes() output; throws InvalidArgument if the
  /// bytes are not a Snapshot message.
  void restore_bytes(const std::string& bytes) {
    Request r;
    if (!r.mutable_restore()->mutable_snapshot()->ParseFromString(bytes)) {
      throw InvalidArgument("the " + name_ + " snapshot blob is corrupt (" +
                            std::to_string(bytes.size()) +
                            " bytes that do not parse as a "
                            "sadr.common.v1.Snapshot)");
    }
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
  /// Tags every Advance (idempotent retries are keyed on run id and step index).
  void set_run_id(std::string run_id) { run_id_ = std::move(run_id); }
  [[nodiscard]] const std::string& run_id() const { return run_id_; }
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
  std::string run_id_;
  common::v1::HandshakeReply hello_;
};

class FluidClient final : public FluidService,
                          public ServiceClient<fluid::v1::FluidRequest, fluid::v1::FluidReply> {
 public:
  FluidClient(const std::string& endpoint, std::chrono::milliseconds timeout)
      : ServiceClient(endpoint, common::v1::SERVICE_KIND_FLUID, timeout) {}
  fluid::v1::InitReply init(const fluid::v1::InitRequest& request);
  /// The geometry asked for by advance() goes through `channel` (must outlive
  /// this client; nullptr = inline arrays).
  void use_geometry_channel(const GeometryChannel* channel) { channel_ = channel; }

  FluidStep advance(std::uint64_t step_index, double dt, bool want_geometry,
                    const SpeciesCounts& counts,
                    const std::vector<std::string>& return_concentrations) override;
  Geometry geometry() override;
  FluidFrame frame(const std::vector<std::string>& species) override;
  std::string snapshot(std::uint64_t step_index) override { return snapshot_bytes(step_index); }
  void restore(const std::string& snapshot) override { restore_bytes(snapshot); }

 private:
  const GeometryChannel* channel_ = nullptr;
};

class SsaClient final : public SsaService,
                        public ServiceClient<ssa::v1::SsaRequest, ssa::v1::SsaReply> {
 public:
  SsaClient(const std::string& endpoint, std::chrono::milliseconds timeout)
      : ServiceClient(endpoint, common::v1::SERVICE_KIND_SSA, timeout) {}
  ssa::v1::InitReply init(const ssa::v1::InitRequest& request);
  /// Geometry in shared memory is read from `channel` (must outlive this
  /// client), whose name is released after the first such advance.
  void use_geometry_channel(GeometryChannel* channel) { channel_ = channel; }

  SsaStep advance(std::uint64_t step_index, double t_end, Geometry geometry,
                  const std::vector<std::string>& return_counts,
                  const SpeciesConcentrations& frozen) override;
  SpeciesCounts counts(const std::vector<std::string>& species) override;
  std::string snapshot(std::uint64_t step_index) override { return snapshot_bytes(step_index); }
  void restore(const std::string& snapshot) override { restore_bytes(snapshot); }

 private:
  GeometryChannel* channel_ = nullptr;
};

}  // namespace sadr::orchestrator
