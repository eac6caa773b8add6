// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/service_clients.hpp"

#include <google/protobuf/io/coded_stream.h>
#include <google/protobuf/io/zero_copy_stream_impl_lite.h>

#include "sadr/common/log.hpp"

namespace sadr::orchestrator {
namespace {

SpeciesCounts counts_from_proto(const common::v1::SpeciesFields& fields) {
  SpeciesCounts out;
  for (const auto& f : fields.species()) {
    out.names.push_back(f.name());
    out.values.emplace_back(f.counts().begin(), f.counts().end());
  }
  return out;
}

void counts_to_proto(const SpeciesCounts& in, common::v1::SpeciesFields& out) {
  for (std::size_t k = 0; k < in.names.size(); ++k) {
    auto* f = out.add_species();
    f->set_name(in.names[k]);
    f->mutable_counts()->Assign(in.values[k].begin(), in.values[k].end());
  }
}

}  // namespace

std::string deterministic_bytes(const google::protobuf::Message& message) {
  std::string out;
  {
    google::protobuf::io::StringOutputStream stream(&out);
    google::protobuf::io::CodedOutputStream coded(&stream);
    coded.SetSerializationDeterministic(true);
    message.SerializeToCodedStream(&coded);
  }
  return out;
}

GeometryChannel GeometryChannel::on_this_host(std::size_t particles) {
  GeometryChannel channel;
  try {
    channel.shm_ = wire::SharedGeometry::create(particles);
    log::info("geometry to ssa_service through shared memory ", channel.shm_->name());
  } catch (const Error& e) {
    log::warn("no shared-memory segment for the geometry (", e.what(),
              "); sending it inline in the messages instead");
  }
  return channel;
}

const std::string& GeometryChannel::segment() const {
  static const std::string none;
  return shm_ ? shm_->name() : none;
}

void GeometryChannel::release() {
  if (shm_) shm_->unlink();
}

FluidSubsteps fluid_substeps(const fluid::v1::InitReply& reply) {
  return {reply.stable_time_step(), reply.limiting_criterion(), reply.max_substep()};
}

fluid::v1::InitReply FluidClient::init(const fluid::v1::InitRequest& request) {
  fluid::v1::FluidRequest r;
  *r.mutable_init() = request;
  return call(r).init();
}

FluidStep FluidClient::advance(std::uint64_t step_index, double dt, bool want_geometry,
                               const SpeciesCounts& counts,
                               const std::vector<std::string>& return_concentrations) {
  fluid::v1::FluidRequest r;
  auto& req = *r.mutable_advance();
  req.set_run_id(run_id());
  req.set_step_index(step_index);
  req.set_time_step(dt);
  req.set_return_state(want_geometry);
  if (want_geometry && channel_ && channel_->shared()) req.set_geometry_shm(channel_->segment());
  if (!counts.empty()) counts_to_proto(counts, *req.mutable_counts());
  for (const auto& name : return_concentrations) req.add_return_concentrations(name);
  auto reply = call(r);
  auto& rep = *reply.mutable_advance();
  FluidStep step;
  for (const auto& f : rep.concentrations().species()) {
    step.concentrations.emplace_back(
        f.name(), std::vector<double>(f.concentrations().begin(), f.concentrations().end()));
  }
  step.time = rep.time();
  step.substeps = rep.substeps();
  step.particles_moved = rep.particles_moved();
  step.compute_seconds = rep.compute_seconds();
  if (rep.stable_time_step() > 0) {  // 0: a service that does not report it
    step.stable_time_step = rep.stable_time_step();
    step.limiting_criterion = rep.limiting_criterion();
  }
  for (const auto& b : rep.body_forces()) {
    BodyForceSample sample;
    sample.name = b.name();
    for (int a = 0; a < 3; ++a) {
      sample.force[a] = a < b.force_size() ? b.force(a) : 0.0;
      sample.torque[a] = a < b.torque_size() ? b.torque(a) : 0.0;
      sample.reference[a] = a < b.reference_size() ? b.reference(a) : 0.0;
    }
    step.body_forces.push_back(std::move(sample));
  }
  if (rep.geometry_generation() > 0) {
    step.geometry = Geometry::shared_memory(rep.geometry_generation());
  } else if (rep.has_particles()) {
    auto arrays = std::make_shared<common::v1::ParticleState>();
    *arrays = std::move(*rep.mutable_particles());
    step.geometry = Geometry::inline_arrays(std::move(arrays));
  }
  return step;
}

Geometry FluidClient::geometry() {
  fluid::v1::FluidRequest r;
  r.mutable_get_state();
  auto reply = call(r);
  auto arrays = std::make_shared<common::v1::ParticleState>();
  *arrays = std::move(*reply.mutable_get_state()->mutable_particles());
  return Geometry::inline_arrays(std::move(arrays));
}

FluidFrame FluidClient::frame(const std::vector<std::string>& species) {
  fluid::v1::FluidRequest r;
  auto& req = *r.mutable_get_state();
  req.set_velocities(true);
  for (const auto& name : species) req.add_species(name);
  const auto reply = call(r);
  const auto& st = reply.get_state();
  FluidFrame out;
  out.particles = wire::from_proto(st.particles(), "fluid_service state");
  for (const auto& f : st.concentrations().species()) {
    out.concentrations.emplace_back(
        f.name(), std::vector<double>(f.concentrations().begin(), f.concentrations().end()));
  }
  return out;
}

ssa::v1::InitReply SsaClient::init(const ssa::v1::InitRequest& request) {
  ssa::v1::SsaRequest r;
  *r.mutable_init() = request;
  return call(r).init();
}

SsaStep SsaClient::advance(std::uint64_t step_index, double t_end, Geometry geometry,
                           const std::vector<std::string>& return_counts,
                           const SpeciesConcentrations& frozen) {
  ssa::v1::SsaRequest r;
  auto& req = *r.mutable_advance();
  req.set_run_id(run_id());
  req.set_step_index(step_index);
  req.set_t_end(t_end);
  const bool shared = geometry.generation() > 0;
  if (shared) {
    if (!channel_ || !channel_->shared()) {
      throw Error(StatusCode::kInternal,
                  "ssa advance: geometry generation " + std::to_string(geometry.generation()) +
                      " is in shared memory, but this client has no segment");
    }
    req.set_geometry_shm(channel_->segment());
    req.set_geometry_generation(geometry.generation());
  } else if (geometry.arrays()) {
    *req.mutable_particles() = std::move(*geometry.arrays());
  }
  for (const auto& name : return_counts) req.add_return_counts(name);
  for (const auto& [name, values] : frozen) {
    auto* f = req.mutable_frozen()->add_species();
    f->set_name(name);
    f->mutable_concentrations()->Assign(values.begin(), values.end());
  }
  auto reply = call(r);
  auto& rep = *reply.mutable_advance();
  // Both services have mapped the segment now.
  if (shared) channel_->release();
  SsaStep step;
  step.time = rep.time();
  step.events = rep.events();
  step.leaped_molecules = rep.leaped_molecules();
  step.graph_seconds = rep.graph_seconds();
  step.nsm_seconds = rep.nsm_seconds();
  step.counts = counts_from_proto(rep.counts());
  return step;
}

SpeciesCounts SsaClient::counts(const std::vector<std::string>& species) {
  ssa::v1::SsaRequest r;
  for (const auto& name : species) r.mutable_get_counts()->add_species(name);
  r.mutable_get_counts();
  return counts_from_proto(call(r).get_counts().counts());
}

}  // namespace sadr::orchestrator
