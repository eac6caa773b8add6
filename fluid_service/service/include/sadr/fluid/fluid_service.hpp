// SPDX-License-Identifier: MIT
/// \file fluid_service.hpp
/// fluid_service request handling: sadr.fluid.v1 messages <-> a FluidBackend
/// chosen by name from the registry.
///
/// Request order: Init first; then Advance / GetState / SetSpecies /
/// Snapshot / Restore; Shutdown ends the service. Restore needs a prior Init
/// with the same model. Advance is idempotent on (run_id, step_index).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "sadr/fluid/backend_registry.hpp"
#include "sadr/fluid/backend_start.hpp"
#include "sadr/fluid/fluid_model.hpp"
#include "sadr/fluid/inflow.hpp"
#include "sadr/fluid/v1/fluid_service.pb.h"
#include "sadr/wire/convert.hpp"
#include "sadr/wire/shared_geometry.hpp"
#include "sadr/wire/typed_handler.hpp"

namespace sadr::fluid {

/// Converts the wire model to the core model (all species, stochastic ones
/// flagged non-deterministic). Throws InvalidArgument naming the field.
FluidModel model_from_proto(const v1::FluidModel& in, std::size_t n_particles);

/// The backend's start (model, particles, concentrations, inflow buffers) from an Init message.
/// Throws InvalidArgument naming the field.
BackendStart start_from_proto(const v1::InitRequest& req);

/// The sub-steps ahead at t = 0 of the backend `request` names, started here on the calling
/// thread (OpenMP threads: SADR_FLUID_THREADS, else the default) from the message alone:
/// what the service's Init replies, without a service, a handler or a serialised message.
/// The plan prints it. Throws what the Init would refuse.
SubstepBound initial_substep_bound(v1::InitRequest request);

class FluidServiceHandler : public wire::TypedHandler<v1::FluidRequest, v1::FluidReply> {
 public:
  FluidServiceHandler();
  ~FluidServiceHandler() override;

 protected:
  void handle_typed(const v1::FluidRequest& request, v1::FluidReply& reply,
                    bool& shutdown) override;

 private:
  void init(const v1::InitRequest& req, v1::InitReply& rep);
  void advance(const v1::AdvanceRequest& req, v1::AdvanceReply& rep);
  void get_state(const v1::GetStateRequest& req, v1::GetStateReply& rep) const;
  void set_species(const v1::SetSpeciesRequest& req);
  /// Back-transfer: concentrations X_is / V_i from copy numbers, with this
  /// service's own volumes V_i = m_i / rho_i. Errors name `where`.
  void set_counts(const common::v1::SpeciesFields& counts, const std::string& where);
  void snapshot(const v1::SnapshotRequest& req, v1::SnapshotReply& rep) const;
  void restore(const v1::RestoreRequest& req);
  /// After a Restore: time, particles (ParticleState::validate, count, dimension) and
  /// the concentrations are what the model allows; throws InvalidArgument.
  void check_restored_state();
  FluidBackend& backend() const;
  /// Re-imposes the inflow buffers' concentrations on the particles inside them.
  void apply_inflows();
  int species(const std::string& name, const std::string& where) const;

  int threads_ = 0;  ///< OpenMP threads of the serving thread (SADR_*_THREADS; 0 = default)
  BackendRegistry registry_;
  std::unique_ptr<FluidBackend> backend_;
  FluidModel model_;
  std::size_t n_particles_ = 0;
  std::string last_run_id_;
  std::uint64_t last_step_ = 0;
  bool have_last_ = false;
  v1::AdvanceReply last_reply_;
  ParticleState scratch_;              ///< state read for Advance(return_state); buffers reused
  wire::SharedGeometry geometry_shm_;  ///< the segment Advance.geometry_shm names (mapped once)
  std::vector<InflowBuffer> inflows_;  ///< applied after Init and after every Advance
  std::vector<double> inflow_values_;  ///< apply_inflows() and set_counts() scratch
};

}  // namespace sadr::fluid
