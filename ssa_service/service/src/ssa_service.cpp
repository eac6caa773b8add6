// SPDX-License-Identifier: MIT
#include "sadr/ssa/ssa_service.hpp"

#include <chrono>
#include <cstdlib>
#include <string>

#ifdef SADR_SERVICE_OPENMP
#include <omp.h>
#endif

#include "sadr/common/log.hpp"
#include "sadr/common/openmp_env.hpp"
#include "sadr/ssa/inflow.hpp"
#include "sadr/ssa/nsm_solver.hpp"
#include "sadr/wire/convert.hpp"

namespace sadr::ssa {
namespace {

constexpr const char* kSnapshotFormat = "sadr.ssa.nsm";

int find_species(const std::vector<std::string>& names, const std::string& name,
                 const std::string& where) {
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return static_cast<int>(i);
  }
  std::string known;
  for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
  throw InvalidArgument(where + ": unknown stochastic species '" + name +
                        "' (known: " + (known.empty() ? "none" : known) + ")");
}

/// Applies the thread count to the calling (serving) thread: an OpenMP ICV of
/// that thread, so embedded services in one process keep their own counts.
void apply_threads(int threads) {
#ifdef SADR_SERVICE_OPENMP
  if (threads > 0 && omp_get_max_threads() != threads) omp_set_num_threads(threads);
#else
  (void)threads;
#endif
}

}  // namespace

SsaServiceHandler::SsaServiceHandler() : threads_(service_threads_from_env("SADR_SSA_THREADS")) {}
SsaServiceHandler::~SsaServiceHandler() = default;

NsmSolver& SsaServiceHandler::solver() const {
  if (!solver_) throw FailedPrecondition("ssa_service is not initialised: send Init first");
  return *solver_;
}

void SsaServiceHandler::handle_typed(const v1::SsaRequest& request, v1::SsaReply& reply,
                                     bool& shutdown) {
  apply_threads(threads_);
  switch (request.body_case()) {
    case v1::SsaRequest::kInit:
      init(request.init(), *reply.mutable_init());
      break;
    case v1::SsaRequest::kAdvance:
      advance(request.advance(), *reply.mutable_advance());
      break;
    case v1::SsaRequest::kGetCounts:
      get_counts(request.get_counts(), *reply.mutable_get_counts());
      break;
    case v1::SsaRequest::kSnapshot:
      snapshot(request.snapshot(), *reply.mutable_snapshot());
      break;
    case v1::SsaRequest::kRestore:
      restore(request.restore());
      reply.mutable_restore();
      break;
    case v1::SsaRequest::kShutdown:
      reply.mutable_shutdown();
      shutdown = true;
      break;
    case v1::SsaRequest::BODY_NOT_SET:
      throw InvalidArgument(
          "empty SsaRequest: set one of init, advance, get_counts, snapshot, "
          "restore, shutdown");
  }
}

void SsaServiceHandler::init(const v1::InitRequest& req, v1::InitReply& rep) {
  const ParticleState particles = wire::from_proto(req.particles(), "init.particles");
  std::vector<std::string> names;
  Model model = model_from_proto(req.model(), particles.size(), names);
  keep_non_fluid_wall_voxels(model, particles);
  auto solver = std::make_unique<NsmSolver>(std::move(model), req.model().seed());
  solver->update_graph(particles);
  for (int k = 0; k < req.counts().species_size(); ++k) {
    const auto& f = req.counts().species(k);
    const std::string where = "init.counts.species[" + std::to_string(k) + "]";
    const int s = find_species(names, f.name(), where);
    if (static_cast<std::size_t>(f.counts_size()) != particles.size()) {
      throw InvalidArgument(where + ".counts has " + std::to_string(f.counts_size()) +
                            " entries, expected one per particle (" +
                            std::to_string(particles.size()) + ")");
    }
    solver->set_counts(s, std::span<const std::int64_t>(f.counts().data(), f.counts_size()));
  }
  auto inflows = inflows_from_proto(req.model(), particles.dimension, names);
  apply_inflows(*solver, inflows);
  solver_ = std::move(solver);
  inflows_ = std::move(inflows);
  species_names_ = std::move(names);
  seed_ = req.model().seed();
  have_last_ = false;
  rep.set_edges(solver_->graph().edge_count());
  log::info("initialised: ", particles.size(), " voxels, ", species_names_.size(),
            " stochastic species, ", solver_->graph().edge_count(), " directed edges");
}

void SsaServiceHandler::advance(const v1::AdvanceRequest& req, v1::AdvanceReply& rep) {
  NsmSolver& s = solver();
  // The copy numbers asked for, after the step (also on a retry: unchanged
  // since); unknown names are refused before stepping.
  std::vector<int> returned;
  for (int k = 0; k < req.return_counts_size(); ++k) {
    returned.push_back(find_species(species_names_, req.return_counts(k),
                                    "advance.return_counts[" + std::to_string(k) + "]"));
  }
  auto add_counts = [&] {
    if (!returned.empty()) copy_counts(returned, *rep.mutable_counts());
  };
  if (have_last_ && req.run_id() == last_run_id_ && req.step_index() == last_step_) {
    rep = last_reply_;  // a retry of the step just done
    add_counts();
    return;
  }
  bool rebuilt = false;
  // Converted before timing: conversion is transfer cost. Kinds and ids may be
  // absent (the fluid's per-step geometry): they are those of the current graph.
  const bool from_shm = !req.geometry_shm().empty();
  if (from_shm) {  // same host: the fluid wrote the geometry into shared memory
    if (geometry_shm_.name() != req.geometry_shm()) {
      geometry_shm_ = wire::SharedGeometry::open(req.geometry_shm(), "advance.geometry_shm");
    }
    geometry_shm_.read(req.geometry_generation(), s.state().graph_inputs(), moved_,
                       "advance.geometry_shm");
  } else if (req.has_particles()) {
    wire::state_from_proto(req.particles(), s.state().graph_inputs(), moved_, "advance.particles");
  }
  const auto t0 = std::chrono::steady_clock::now();
  if (from_shm || req.has_particles()) rebuilt = s.update_graph(moved_);
  apply_inflows(s, inflows_);
  const auto t1 = std::chrono::steady_clock::now();
  if (!(req.t_end() >= s.time())) {
    throw InvalidArgument("advance.t_end = " + format_value(req.t_end()) +
                          " is before the current time " + format_value(s.time()));
  }
  set_frozen(s, req);
  const std::uint64_t before = s.events();
  const std::uint64_t leaped_before = s.leaped_molecules();
  const std::uint64_t windows_before = s.leap_windows();
  s.advance(req.t_end());
  rep.set_graph_seconds(std::chrono::duration<double>(t1 - t0).count());
  rep.set_nsm_seconds(std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count());
  rep.set_step_index(req.step_index());
  rep.set_time(s.time());
  rep.set_events(s.events() - before);
  rep.set_leaped_molecules(s.leaped_molecules() - leaped_before);
  rep.set_leap_windows(s.leap_windows() - windows_before);
  rep.set_graph_rebuilt(rebuilt);
  last_run_id_ = req.run_id();
  last_step_ = req.step_index();
  last_reply_ = rep;
  have_last_ = true;
  add_counts();
}

void SsaServiceHandler::set_frozen(NsmSolver& s, const v1::AdvanceRequest& req) {
  if (!s.state().reactions().has_external_laws()) return;
  const auto& names = s.model().frozen_species;
  const std::size_t n = s.state().voxel_count();
  std::vector<double>& frozen = frozen_scratch_;
  frozen.assign(names.size() * n, 0.0);
  for (std::size_t k = 0; k < names.size(); ++k) {
    const common::v1::SpeciesField* field = nullptr;
    for (const auto& f : req.frozen().species()) {
      if (f.name() == names[k]) field = &f;
    }
    if (!field || static_cast<std::size_t>(field->concentrations_size()) != n) {
      throw InvalidArgument(
          "advance.frozen: the concentrations of the deterministic species '" + names[k] +
              "' (read by a hybrid reaction's law) are " +
              (field ? std::to_string(field->concentrations_size()) + " values" : "missing") +
              "; required: one per particle (" + std::to_string(n) + ") every step",
          {{"field", "advance.frozen"}, {"value", names[k]}});
    }
    std::copy(field->concentrations().begin(), field->concentrations().end(),
              frozen.begin() + static_cast<std::ptrdiff_t>(k * n));
  }
  s.set_inputs(s.time(), frozen);  // held over [time, t_end]: the stage's start values
}

void SsaServiceHandler::get_counts(const v1::GetCountsRequest& req, v1::GetCountsReply& rep) const {
  const NsmSolver& s = solver();
  std::vector<int> which;
  if (req.species_size() == 0) {
    for (std::size_t i = 0; i < species_names_.size(); ++i) which.push_back(static_cast<int>(i));
  } else {
    for (int k = 0; k < req.species_size(); ++k) {
      which.push_back(find_species(species_names_, req.species(k),
                                   "get_counts.species[" + std::to_string(k) + "]"));
    }
  }
  copy_counts(which, *rep.mutable_counts());
  rep.set_time(s.time());
}

void SsaServiceHandler::copy_counts(const std::vector<int>& which,
                                    common::v1::SpeciesFields& out) const {
  const NsmSolver& s = solver();
  for (int sp : which) {
    auto* f = out.add_species();
    f->set_name(species_names_[static_cast<std::size_t>(sp)]);
    const auto c = s.counts(sp);
    f->mutable_counts()->Assign(c.begin(), c.end());
  }
}

void SsaServiceHandler::snapshot(const v1::SnapshotRequest& req, v1::SnapshotReply& rep) const {
  const NsmSolver& s = solver();
  auto* snap = rep.mutable_snapshot();
  snap->set_format(kSnapshotFormat);
  snap->set_format_version(NsmSolver::kSnapshotVersion);
  snap->set_step_index(req.step_index());
  snap->set_time(s.time());
  snap->set_blob(s.save());
  (*snap->mutable_metadata())["seed"] = std::to_string(seed_);
  (*snap->mutable_metadata())["voxels"] = std::to_string(s.state().voxel_count());
  (*snap->mutable_metadata())["events"] = std::to_string(s.events());
}

void SsaServiceHandler::restore(const v1::RestoreRequest& req) {
  NsmSolver& s = solver();
  const auto& snap = req.snapshot();
  if (snap.format() != kSnapshotFormat || snap.format_version() != NsmSolver::kSnapshotVersion) {
    throw InvalidArgument("restore: snapshot format '" + snap.format() + "' v" +
                          std::to_string(snap.format_version()) + " is not '" + kSnapshotFormat +
                          "' v" + std::to_string(NsmSolver::kSnapshotVersion));
  }
  s.restore(snap.blob());
  have_last_ = false;
}

}  // namespace sadr::ssa
