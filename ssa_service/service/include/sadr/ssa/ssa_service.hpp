// SPDX-License-Identifier: MIT
/// \file ssa_service.hpp
/// ssa_service request handling: sadr.ssa.v1 messages <-> sadr::ssa::NsmSolver.
///
/// Request order: Init (model, particles, initial counts) first; then any of
/// Advance / GetCounts / Snapshot / Restore; Shutdown ends the service.
/// Restore needs a prior Init with the same model (the snapshot checks it).
/// Advance is idempotent on (run_id, step_index): a resent request gets the
/// stored reply without stepping again (safe retries after a timeout).
/// Inflow buffers (inflow.hpp) are re-imposed at Init and at the start of
/// every Advance, after the graph update.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "sadr/ssa/inflow.hpp"
#include "sadr/ssa/model.hpp"
#include "sadr/ssa/v1/ssa_service.pb.h"
#include "sadr/wire/shared_geometry.hpp"
#include "sadr/wire/typed_handler.hpp"

namespace sadr::ssa {

class NsmSolver;

/// Converts the wire model to the core model. Only species with
/// stochastic = true are kept (in message order); `species_names` receives
/// them. Throws InvalidArgument naming the field (e.g. "init.model.reactions[2]").
/// Converts and validates the model's inflows (throws InvalidArgument naming
/// "init.model.inflows[k].<field>").
std::vector<InflowBuffer> inflows_from_proto(const v1::SsaModel& model, int dimension,
                                             const std::vector<std::string>& species_names);

Model model_from_proto(const v1::SsaModel& in, std::size_t n_particles,
                       std::vector<std::string>& species_names);

/// A scene's wall conditions apply to the non-fluid particles of their region
/// (docs/scene-format.md "boundaries"): drops the fluid particles from the voxel lists of the
/// reservoirs and free walls, which the core takes as lists of wall particles. Fluid particles
/// lie in a geometric region wherever they have moved into it (a scene started from a frame).
/// Throws InvalidArgument when a list had particles and none of them is non-fluid (an empty
/// list would mean every wall).
void keep_non_fluid_wall_voxels(Model& model, const ParticleState& particles);

class SsaServiceHandler : public wire::TypedHandler<v1::SsaRequest, v1::SsaReply> {
 public:
  SsaServiceHandler();
  ~SsaServiceHandler() override;

 protected:
  void handle_typed(const v1::SsaRequest& request, v1::SsaReply& reply, bool& shutdown) override;

 private:
  int threads_ = 0;  ///< OpenMP threads of the serving thread (SADR_*_THREADS; 0 = default)
  void init(const v1::InitRequest& req, v1::InitReply& rep);
  void advance(const v1::AdvanceRequest& req, v1::AdvanceReply& rep);
  /// Hybrid reactions / laws of t: the stage's inputs from advance.frozen (refused if
  /// a frozen species is missing or has the wrong length); nothing without such laws.
  void set_frozen(NsmSolver& s, const v1::AdvanceRequest& req);
  void get_counts(const v1::GetCountsRequest& req, v1::GetCountsReply& rep) const;
  /// Appends the copy numbers of species `which` (indices) to `out`.
  void copy_counts(const std::vector<int>& which, common::v1::SpeciesFields& out) const;
  void snapshot(const v1::SnapshotRequest& req, v1::SnapshotReply& rep) const;
  void restore(const v1::RestoreRequest& req);
  NsmSolver& solver() const;

  std::unique_ptr<NsmSolver> solver_;
  std::vector<std::string> species_names_;
  std::vector<InflowBuffer> inflows_;   ///< re-imposed at Init and every Advance
  ParticleState moved_;                 ///< the last Advance's particles (buffers reused)
  std::vector<double> frozen_scratch_;  ///< set_frozen's concentrations (buffer reused)
  wire::SharedGeometry geometry_shm_;   ///< the segment Advance.geometry_shm names (mapped once)
  std::uint64_t seed_ = 0;
  // Idempotent advance: the last (run_id, step_index) and its reply.
  std::string last_run_id_;
  std::uint64_t last_step_ = 0;
  bool have_last_ = false;
  v1::AdvanceReply last_reply_;
};

}  // namespace sadr::ssa
