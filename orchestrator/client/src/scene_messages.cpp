// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/scene_messages.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include <google/protobuf/io/coded_stream.h>
#include <google/protobuf/io/zero_copy_stream_impl_lite.h>

#include "sadr/orchestrator/frame_output.hpp"
#include "sadr/orchestrator/hash.hpp"
#include "sadr/orchestrator/scene_wall_tangents.hpp"
#include "sadr/orchestrator/splitting_loop.hpp"
#include "sadr/wire/convert.hpp"
#include "sadr/wire/model_proto.hpp"

namespace sadr::orchestrator {
namespace {

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

/// The model's message, the regions it names into `regions_used`.
void add_species(const Species& in, common::v1::Species& out, std::set<std::string>& regions_used) {
  wire::to_proto(in, out);
  for (const auto& b : in.boundaries) {
    if (b.condition != BoundaryCondition::kInflow && !b.region.empty())
      regions_used.insert(b.region);
  }
}

void add_reaction(const Reaction& in, common::v1::Reaction& out,
                  std::set<std::string>& regions_used) {
  wire::to_proto(in, out);
  regions_used.insert(in.regions.begin(), in.regions.end());
}

template <class RepeatedRegions>
void add_regions(const Scene& scene, const std::set<std::string>& used, RepeatedRegions* out) {
  for (const auto& name : used) {
    const Region* r = scene.find_region(name);
    if (!r) throw InvalidArgument("unknown region '" + name + "'");
    auto* m = out->Add();
    m->set_name(name);
    m->mutable_particles()->Assign(r->particles.begin(), r->particles.end());
  }
}

/// fluid.wall_planes (the Morris wall surfaces) into `out`, their regions into `regions_used`.
void add_wall_planes(const Scene& scene,
                     google::protobuf::RepeatedPtrField<common::v1::WallPlane>& out,
                     std::set<std::string>& regions_used) {
  for (const auto& p : scene.fluid.wall_planes) {
    wire::to_proto(p, *out.Add());
    regions_used.insert(p.region);
  }
}

/// The inflow buffers of species `s` as boxes (a channel is unbounded across its axis),
/// for ssa::v1::SsaModel (stochastic species) or fluid::v1::FluidModel (deterministic).
template <class ServiceModel>
void add_inflows(const Scene& scene, const Species& s, ServiceModel& m) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  for (const auto& b : s.boundaries) {
    if (b.condition != BoundaryCondition::kInflow) continue;
    const Region* r = scene.find_region(b.region);
    if (!r) throw InvalidArgument("inflow of '" + s.name + "': unknown region '" + b.region + "'");
    auto* in = m.add_inflows();
    in->set_species(s.name);
    in->set_concentration(b.value);
    for (int a = 0; a < scene.particles.dimension; ++a) {
      const bool box = r->shape == RegionShape::kBox;
      const bool across = r->shape == RegionShape::kChannel && r->axis == a;
      in->add_lower(box ? r->lower[a] : across ? r->axis_lower : -kInf);
      in->add_upper(box ? r->upper[a] : across ? r->axis_upper : kInf);
    }
  }
}

fluid::v1::DensityMode density_mode(const std::string& name) {
  if (name == "continuity") return fluid::v1::DENSITY_MODE_CONTINUITY;
  if (name == "summation") return fluid::v1::DENSITY_MODE_SUMMATION;
  throw InvalidArgument("fluid.density_mode = '" + name + "' (allowed: continuity, summation)");
}

fluid::v1::WallModel wall_model(const std::string& name) {
  if (name == "stationary") return fluid::v1::WALL_MODEL_STATIONARY;
  if (name == "morris") return fluid::v1::WALL_MODEL_MORRIS;
  if (name == "adami") return fluid::v1::WALL_MODEL_ADAMI;
  throw InvalidArgument("fluid.wall_model = '" + name + "' (allowed: stationary, morris, adami)");
}

}  // namespace

fluid::v1::InitRequest make_fluid_init(const Scene& scene, const Plan& plan, std::uint64_t seed) {
  fluid::v1::InitRequest init;
  auto* m = init.mutable_model();
  const auto& f = scene.fluid;
  m->set_backend(f.backend);
  wire::to_proto(scene.box, *m->mutable_box());
  m->set_smoothing_length(f.smoothing_length);
  m->set_kernel(f.kernel);
  m->set_reference_density(f.reference_density);
  m->set_sound_speed(f.sound_speed);
  m->set_shear_viscosity(f.shear_viscosity);
  m->set_temperature(f.temperature);
  for (double g : f.gravity) m->add_gravity(g);
  m->set_seed(seed);
  m->set_max_time_step(f.max_time_step);
  m->set_force_time_step(f.force_time_step);
  m->set_density_mode(density_mode(f.density_mode));
  m->set_wall_model(wall_model(f.wall_model));
  for (const auto& [k, v] : f.parameters) (*m->mutable_parameters())[k] = v;
  for (const auto& [k, v] : f.files) (*m->mutable_files())[k] = v;
  if (f.open_boundary) wire::to_proto(*f.open_boundary, *m->mutable_open_boundary());
  if (f.boussinesq) {
    m->set_buoyancy_species(f.boussinesq->species);
    m->set_buoyancy_coefficient(f.boussinesq->coefficient);
    m->set_buoyancy_reference(f.boussinesq->reference);
    for (double d : f.boussinesq->direction) m->add_buoyancy_direction(d);
  }
  std::set<std::string> regions_used;
  for (const auto& s : scene.species) {
    if (!contains(plan.fluid_species, s.name)) continue;
    add_species(s, *m->add_species(), regions_used);
    if (!s.stochastic) {
      add_inflows(scene, s, *m);  // a stochastic species' buffer is held by ssa_service
      auto* c = init.mutable_concentrations()->add_species();
      c->set_name(s.name);
      c->mutable_concentrations()->Assign(s.initial.begin(), s.initial.end());
    }
  }
  for (const auto& r : scene.reactions) {
    if (!r.stochastic) add_reaction(r, *m->add_reactions(), regions_used);
  }
  add_wall_planes(scene, *m->mutable_wall_planes(), regions_used);
  // Morris walls made by the geometry: every wall particle's tangent plane (unset otherwise).
  if (const WallTangents t = scene_wall_tangents(scene); !t.empty()) {
    wire::to_proto(t, *m->mutable_wall_tangents());
  }
  for (const auto& body : f.body_forces) {  // fluid.body_forces: regions of wall particles
    m->add_body_forces(body);
    regions_used.insert(body);
  }
  // Solid bodies whose walls move (motion: {moves: true}): their regions carry the motion.
  std::map<std::string, RigidMotion> moving;
  if (scene.geometry) {
    for (const auto& b : scene.geometry->bodies) {
      if (!b.moving) continue;
      moving.emplace(b.name, *b.moving);
      regions_used.insert(b.name);
    }
  }
  add_regions(scene, regions_used, m->mutable_regions());
  for (auto& r : *m->mutable_regions()) {
    const auto it = moving.find(r.name());
    if (it == moving.end()) continue;
    const RigidMotion& mo = it->second;
    auto* out = r.mutable_motion();
    out->mutable_velocity()->Assign(mo.velocity.begin(), mo.velocity.end());
    out->set_angular_velocity(mo.angular_velocity);
    out->mutable_center()->Assign(mo.center.begin(), mo.center.end());
    out->mutable_axis()->Assign(mo.axis.begin(), mo.axis.end());
  }
  wire::to_proto(scene.particles, *init.mutable_particles(), /*with_velocities=*/true);
  return init;
}

ssa::v1::InitRequest make_ssa_init(const Scene& scene, const Plan& plan, std::uint64_t seed,
                                   const ParticleState& particles) {
  ssa::v1::InitRequest init;
  auto* m = init.mutable_model();
  wire::to_proto(scene.box, *m->mutable_box());
  m->set_smoothing_length(scene.fluid.smoothing_length);
  m->set_regularization(scene.ssa.regularization);
  m->set_convention(wire::to_proto(scene.ssa.convention));
  if (scene.ssa.method == model::SsaMethod::kAdaptive) {  // unset for exact: the same bytes
    m->set_method(ssa::v1::SSA_METHOD_ADAPTIVE);
    m->set_tolerance(scene.ssa.tolerance);
  }
  m->set_seed(seed);
  std::set<std::string> regions_used;
  for (const auto& s : scene.species) {
    if (!s.stochastic || !contains(plan.ssa_species, s.name)) continue;
    add_species(s, *m->add_species(), regions_used);
    add_inflows(scene, s, *m);
    auto* c = init.mutable_counts()->add_species();
    c->set_name(s.name);
    auto* counts = c->mutable_counts();
    counts->Reserve(static_cast<int>(s.initial.size()));
    for (double v : s.initial) counts->Add(static_cast<std::int64_t>(std::llround(v)));
  }
  for (const auto& r : scene.reactions) {
    if (r.stochastic) add_reaction(r, *m->add_reactions(), regions_used);
  }
  for (const auto& s : plan.frozen_species) m->add_frozen_species(s);
  // Morris walls (fluid.wall_model morris): the stochastic species' Dirichlet reservoirs hold
  // their values on the same wall surfaces as the fluid's deterministic species.
  bool ssa_dirichlet = false;
  for (const auto& s : scene.species) {
    if (!s.stochastic || !contains(plan.ssa_species, s.name)) continue;
    for (const auto& b : s.boundaries)
      ssa_dirichlet |= b.condition == BoundaryCondition::kDirichlet;
  }
  if (scene.fluid.wall_model == "morris" && ssa_dirichlet) {
    add_wall_planes(scene, *m->mutable_wall_planes(), regions_used);
    if (const WallTangents t = scene_wall_tangents(scene); !t.empty()) {
      wire::to_proto(t, *m->mutable_wall_tangents());
    }
  }
  add_regions(scene, regions_used, m->mutable_regions());
  wire::to_proto(particles, *init.mutable_particles(), /*with_velocities=*/false);
  return init;
}

namespace {

std::string init_bytes(const google::protobuf::MessageLite& m) {
  std::string out;
  {
    google::protobuf::io::StringOutputStream stream(&out);
    google::protobuf::io::CodedOutputStream coded(&stream);
    coded.SetSerializationDeterministic(true);
    m.SerializeToCodedStream(&coded);
  }
  return out;
}

/// Where a law was written ("file:line", for messages) is not its meaning; a backend file is
/// its bytes, not its path.
void strip_origins(google::protobuf::RepeatedPtrField<common::v1::Reaction>& reactions) {
  for (auto& r : reactions) {
    if (r.has_law()) r.mutable_law()->clear_origin();
  }
}

fluid::v1::InitRequest meaning_of_fluid_init(const Scene& scene, const Plan& plan,
                                             std::uint64_t seed) {
  fluid::v1::InitRequest fluid = make_fluid_init(scene, plan, seed);
  strip_origins(*fluid.mutable_model()->mutable_reactions());
  for (auto& [key, path] : *fluid.mutable_model()->mutable_files()) path = file_hash(path);
  return fluid;
}

}  // namespace

std::string scene_meaning_hash(const Scene& scene, const Plan& plan) {
  const fluid::v1::InitRequest fluid = meaning_of_fluid_init(scene, plan, scene.seed);
  ssa::v1::InitRequest ssa = make_ssa_init(scene, plan, scene.seed, scene.particles);
  strip_origins(*ssa.mutable_model()->mutable_reactions());
  std::string bytes = init_bytes(fluid) + init_bytes(ssa);
  // The rest of the meaning as text (appends only: GCC 12 misreports chains of operator+).
  std::string text;
  auto add = [&text](std::initializer_list<std::string_view> parts) {
    for (const auto p : parts) text.append(p);
    text.push_back('\n');
  };
  add({"name=", scene.name});
  for (const auto& a : scene.assigned) add({"assigned ", a.name, "=", a.expanded});
  for (const auto& s : scene.species) add({"species ", s.name});  // the file's order
  add({"time ", format_value(scene.time.coupling_step), " ", format_value(scene.time.end), " ",
       to_string(scene.time.splitting)});
  const OutputSettings& o = scene.output;
  for (double t : o.times) add({"output ", format_value(t)});
  for (auto f : o.formats) add({"format ", to_string(f)});
  for (const auto& s : o.species) add({"written ", s});
  add({"checkpoint_every ", format_value(o.checkpoint_every), " vtk_encoding ",
       std::to_string(static_cast<int>(o.vtk_encoding))});
  for (const auto& ob : o.observables) {
    add({"observable ", ob.name, " ", ob.species, " ", ob.region, ob.mean ? " mean" : " sum"});
  }
  return content_hash(bytes + text);
}

std::string fluid_key(const Scene& scene, const Plan& plan) {
  // The seed is the realization's: a fluid that draws no random numbers ignores it (flow
  // replay is allowed only then, Plan::flow_replay_allowed).
  std::string bytes = init_bytes(meaning_of_fluid_init(scene, plan, 0));
  std::string text = "fluid key 1\n";
  auto add = [&text](std::initializer_list<std::string_view> parts) {
    for (const auto p : parts) text.append(p);
    text.push_back('\n');
  };
  // The coupling schedule: which calls the loop makes of the fluid, and when.
  const LoopSettings s = make_loop_settings(scene, plan);
  add({"time ", format_value(s.tau), " ", format_value(s.t_end), " ", to_string(s.splitting)});
  add({"fluid_stepping ", s.fluid_stepping ? "1" : "0", " calls_per_step ",
       std::to_string(s.fluid_calls_per_step), " geometry_each_step ",
       s.geometry_each_step ? "1" : "0", " frame_to_frame ", s.frame_to_frame ? "1" : "0"});
  for (const auto& b : s.back_transfer) add({"back_transfer ", b});
  for (const auto& f : s.frozen) add({"frozen ", f});
  for (double t : s.output_times) add({"output ", format_value(t)});
  for (const auto& f : frame_fluid_species(scene)) add({"frame species ", f});
  return content_hash(bytes + text);
}

}  // namespace sadr::orchestrator
