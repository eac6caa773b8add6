// SPDX-License-Identifier: MIT
#include "sadr/fluid/fluid_service.hpp"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <string>

#ifdef SADR_SERVICE_OPENMP
#include <omp.h>
#endif

#include "sadr/common/log.hpp"
#include "sadr/common/openmp_env.hpp"
#include "sadr/fluid/builtin_backends.hpp"
#include "sadr/wire/convert.hpp"

namespace sadr::fluid {
namespace {
constexpr std::uint32_t kSnapshotVersion = 1;  // of the envelope; the blob has its own

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

SubstepBound initial_substep_bound(v1::InitRequest request) {
  apply_threads(service_threads_from_env("SADR_FLUID_THREADS"));
  BackendRegistry registry;
  register_builtin_backends(registry);
  auto backend = registry.create(request.model().backend());
  const BackendStart start = start_from_proto(request);
  request = v1::InitRequest{};  // the message's copy of the particles is not needed any more
  ParticleState scratch;
  std::vector<double> values;
  return start_backend(*backend, start, scratch, values);
}

FluidServiceHandler::FluidServiceHandler()
    : threads_(service_threads_from_env("SADR_FLUID_THREADS")) {
  register_builtin_backends(registry_);
}
FluidServiceHandler::~FluidServiceHandler() = default;

FluidBackend& FluidServiceHandler::backend() const {
  if (!backend_) throw FailedPrecondition("fluid_service is not initialised: send Init first");
  return *backend_;
}

int FluidServiceHandler::species(const std::string& name, const std::string& where) const {
  const int s = model_.species_index(name);
  if (s < 0) {
    std::string known;
    for (const auto& sp : model_.species) known += (known.empty() ? "" : ", ") + sp.def.name;
    throw InvalidArgument(where + ": unknown species '" + name +
                          "' (known: " + (known.empty() ? "none" : known) + ")");
  }
  return s;
}

void FluidServiceHandler::handle_typed(const v1::FluidRequest& request, v1::FluidReply& reply,
                                       bool& shutdown) {
  apply_threads(threads_);
  switch (request.body_case()) {
    case v1::FluidRequest::kInit:
      init(request.init(), *reply.mutable_init());
      break;
    case v1::FluidRequest::kAdvance:
      advance(request.advance(), *reply.mutable_advance());
      break;
    case v1::FluidRequest::kGetState:
      get_state(request.get_state(), *reply.mutable_get_state());
      break;
    case v1::FluidRequest::kSetSpecies:
      set_species(request.set_species());
      reply.mutable_set_species();
      break;
    case v1::FluidRequest::kSnapshot:
      snapshot(request.snapshot(), *reply.mutable_snapshot());
      break;
    case v1::FluidRequest::kRestore:
      restore(request.restore());
      reply.mutable_restore();
      break;
    case v1::FluidRequest::kShutdown:
      reply.mutable_shutdown();
      shutdown = true;
      break;
    case v1::FluidRequest::BODY_NOT_SET:
      throw InvalidArgument(
          "empty FluidRequest: set one of init, advance, get_state, "
          "set_species, snapshot, restore, shutdown");
  }
}

void FluidServiceHandler::init(const v1::InitRequest& req, v1::InitReply& rep) {
  auto backend = registry_.create(req.model().backend());
  BackendStart start = start_from_proto(req);
  const SubstepBound bound = start_backend(*backend, start, scratch_, inflow_values_);
  backend_ = std::move(backend);
  model_ = std::move(start.model);
  n_particles_ = start.particles.size();
  have_last_ = false;
  inflows_ = std::move(start.inflows);
  // The sub-steps ahead at the initial state (with the inflow buffers' values), for the plan.
  rep.set_stable_time_step(bound.limit);
  rep.set_limiting_criterion(bound.limit_name);
  rep.set_max_substep(bound.dt);
  log::info("initialised backend '", backend_->name(), "' with ", n_particles_, " particles, ",
            model_.species.size(), " species");
}

void FluidServiceHandler::advance(const v1::AdvanceRequest& req, v1::AdvanceReply& rep) {
  FluidBackend& b = backend();
  // The state read after the step (unchanged on a retry, so read again rather
  // than cached: the reply cache stays small).
  auto add_state = [&] {
    if (!req.return_state()) return;
    b.read_state(scratch_);
    if (!req.geometry_shm().empty()) {  // same host: through shared memory
      if (geometry_shm_.name() != req.geometry_shm()) {
        geometry_shm_ = wire::SharedGeometry::open(req.geometry_shm(), "advance.geometry_shm");
      }
      rep.clear_particles();
      rep.set_geometry_generation(geometry_shm_.write(scratch_, b.time()));
      return;
    }
    wire::geometry_to_proto(scratch_, *rep.mutable_particles());
    rep.mutable_particles()->set_time(b.time());
  };
  // Hybrid reactions: the deterministic concentrations the next SSA stage holds frozen.
  auto add_concentrations = [&] {
    for (int k = 0; k < req.return_concentrations_size(); ++k) {
      const int s = species(req.return_concentrations(k),
                            "advance.return_concentrations[" + std::to_string(k) + "]");
      auto* f = rep.mutable_concentrations()->add_species();
      f->set_name(req.return_concentrations(k));
      const auto& c = b.concentrations(s);
      f->mutable_concentrations()->Assign(c.begin(), c.end());
    }
  };
  if (have_last_ && req.run_id() == last_run_id_ && req.step_index() == last_step_) {
    rep = last_reply_;
    add_state();
    add_concentrations();
    return;
  }
  if (!(req.time_step() > 0)) {
    throw InvalidArgument("advance.time_step = " + format_value(req.time_step()) +
                          " (allowed: > 0)");
  }
  if (req.has_counts()) set_counts(req.counts(), "advance.counts");
  const auto t0 = std::chrono::steady_clock::now();
  const StepReport r = b.advance(req.step_index(), req.time_step());
  rep.set_compute_seconds(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  rep.set_step_index(req.step_index());
  rep.set_time(r.time);
  rep.set_substeps(r.substeps);
  rep.set_max_speed(r.max_speed);
  rep.set_min_density(r.min_density);
  rep.set_max_density(r.max_density);
  rep.set_particles_moved(r.particles_moved);
  rep.set_stable_time_step(r.stable_dt);
  rep.set_limiting_criterion(r.limiting_criterion);
  for (const auto& f : r.body_forces) {
    auto* out = rep.add_body_forces();
    out->set_name(f.name);
    out->mutable_force()->Assign(f.force.begin(), f.force.end());
    out->mutable_torque()->Assign(f.torque.begin(), f.torque.end());
    out->mutable_reference()->Assign(f.reference.begin(), f.reference.end());
  }
  apply_inflows();
  last_run_id_ = req.run_id();
  last_step_ = req.step_index();
  last_reply_ = rep;
  have_last_ = true;
  add_state();
  add_concentrations();
}

void FluidServiceHandler::apply_inflows() {
  if (!inflows_.empty()) fluid::apply_inflows(backend(), inflows_, scratch_, inflow_values_);
}

void FluidServiceHandler::get_state(const v1::GetStateRequest& req, v1::GetStateReply& rep) const {
  const FluidBackend& b = backend();
  ParticleState state;
  b.read_state(state);
  wire::to_proto(state, *rep.mutable_particles(), req.velocities());
  rep.mutable_particles()->set_time(b.time());
  for (int k = 0; k < req.species_size(); ++k) {
    const int s = species(req.species(k), "get_state.species[" + std::to_string(k) + "]");
    auto* f = rep.mutable_concentrations()->add_species();
    f->set_name(req.species(k));
    const auto& c = b.concentrations(s);
    f->mutable_concentrations()->Assign(c.begin(), c.end());
  }
}

void FluidServiceHandler::set_species(const v1::SetSpeciesRequest& req) {
  FluidBackend& b = backend();
  for (int k = 0; k < req.concentrations().species_size(); ++k) {
    const auto& f = req.concentrations().species(k);
    const std::string where = "set_species.concentrations.species[" + std::to_string(k) + "]";
    const int s = species(f.name(), where);
    if (static_cast<std::size_t>(f.concentrations_size()) != n_particles_) {
      throw InvalidArgument(where + " has " + std::to_string(f.concentrations_size()) +
                            " values, expected " + std::to_string(n_particles_));
    }
    b.set_concentrations(
        s, std::span<const double>(f.concentrations().data(), f.concentrations_size()));
  }
}

void FluidServiceHandler::set_counts(const common::v1::SpeciesFields& counts,
                                     const std::string& where) {
  FluidBackend& b = backend();
  b.read_state(scratch_);  // the volumes V_i = m_i / rho_i of the current state
  for (int k = 0; k < counts.species_size(); ++k) {
    const auto& f = counts.species(k);
    const std::string at = where + ".species[" + std::to_string(k) + "]";
    const int s = species(f.name(), at);
    if (static_cast<std::size_t>(f.counts_size()) != n_particles_) {
      throw InvalidArgument(at + " has " + std::to_string(f.counts_size()) + " counts, expected " +
                            std::to_string(n_particles_));
    }
    std::vector<double>& c = inflow_values_;  // scratch reused: no allocation per step
    c.resize(n_particles_);
    for (std::size_t i = 0; i < n_particles_; ++i) {
      c[i] = static_cast<double>(f.counts(static_cast<int>(i))) / scratch_.volume(i);
    }
    b.set_concentrations(s, c);
  }
}

void FluidServiceHandler::snapshot(const v1::SnapshotRequest& req, v1::SnapshotReply& rep) const {
  const FluidBackend& b = backend();
  auto* snap = rep.mutable_snapshot();
  snap->set_format("sadr.fluid." + std::string(b.name()));
  snap->set_format_version(kSnapshotVersion);
  snap->set_step_index(req.step_index());
  snap->set_time(b.time());
  snap->set_blob(b.save());
  (*snap->mutable_metadata())["backend"] = std::string(b.name());
  (*snap->mutable_metadata())["particles"] = std::to_string(n_particles_);
  (*snap->mutable_metadata())["seed"] = std::to_string(model_.seed);
}

void FluidServiceHandler::restore(const v1::RestoreRequest& req) {
  FluidBackend& b = backend();
  const auto& snap = req.snapshot();
  const std::string want = "sadr.fluid." + std::string(b.name());
  if (snap.format() != want || snap.format_version() != kSnapshotVersion) {
    throw InvalidArgument("restore: snapshot format '" + snap.format() + "' v" +
                          std::to_string(snap.format_version()) + " does not match backend '" +
                          std::string(b.name()) + "' (" + want + " v" +
                          std::to_string(kSnapshotVersion) + ")");
  }
  // A blob that reads back into a state the model cannot have (a non-finite
  // position or concentration, another particle count; found by fuzz_fluid_requests)
  // is refused, and the state before the Restore is put back.
  const std::string before = b.save();
  try {
    b.restore(snap.blob());
    check_restored_state();
  } catch (...) {
    b.restore(before);
    throw;
  }
  have_last_ = false;
}

void FluidServiceHandler::check_restored_state() {
  FluidBackend& b = backend();
  if (!(std::isfinite(b.time()) && b.time() >= 0)) {
    throw InvalidArgument("restore: the blob's time = " + format_value(b.time()) +
                          " (must be finite and >= 0)");
  }
  b.read_state(scratch_);
  try {
    scratch_.validate();
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(std::string("restore: the blob's ") + e.what());
  }
  if (scratch_.size() != n_particles_ || scratch_.dimension != model_.box.dimension) {
    throw InvalidArgument("restore: the blob holds " + std::to_string(scratch_.size()) +
                          " particles in " + std::to_string(scratch_.dimension) + "D, the model " +
                          std::to_string(n_particles_) + " in " +
                          std::to_string(model_.box.dimension) + "D");
  }
  for (std::size_t k = 0; k < model_.species.size(); ++k) {
    const auto& c = b.concentrations(static_cast<int>(k));
    for (std::size_t i = 0; i < c.size(); ++i) {
      if (!std::isfinite(c[i])) {
        throw InvalidArgument("restore: the blob's concentration of '" +
                              model_.species[k].def.name + "' at particle " + std::to_string(i) +
                              " = " + format_value(c[i]) + " (must be finite)");
      }
    }
  }
}

}  // namespace sadr::fluid
