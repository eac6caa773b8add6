// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/scene_messages.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "sadr/wire/convert.hpp"

namespace sadr::orchestrator {
namespace {

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

void to_proto(const Species& in, common::v1::Species& out, std::set<std::string>& regions_used) {
  out.set_name(in.name);
  out.set_stochastic(in.stochastic);
  out.set_diffusivity(in.diffusivity);
  for (const auto& b : in.boundaries) {
    if (b.condition == BoundaryCondition::kInflow) continue;  // not a wall: make_ssa_init
    auto* w = out.add_walls();
    w->set_region(b.region);
    w->set_value(b.value);
    switch (b.condition) {
      case BoundaryCondition::kNone:
        w->set_condition(common::v1::WALL_CONDITION_NONE);
        break;
      case BoundaryCondition::kDirichlet:
        w->set_condition(common::v1::WALL_CONDITION_DIRICHLET);
        break;
      case BoundaryCondition::kNeumann:
        w->set_condition(common::v1::WALL_CONDITION_NEUMANN);
        break;
      case BoundaryCondition::kFree:
        w->set_condition(common::v1::WALL_CONDITION_FREE);
        break;
      case BoundaryCondition::kInflow:
        break;
    }
    if (!b.region.empty()) regions_used.insert(b.region);
  }
}

void to_proto(const Reaction& in, common::v1::Reaction& out, std::set<std::string>& regions_used) {
  out.set_name(in.name);
  for (const auto& e : in.reactants) {
    auto* p = out.add_reactants();
    p->set_species(e.species);
    p->set_count(e.count);
  }
  for (const auto& e : in.products) {
    auto* p = out.add_products();
    p->set_species(e.species);
    p->set_count(e.count);
  }
  out.set_rate(in.rate);
  if (in.law) wire::to_proto(*in.law, *out.mutable_law());
  for (auto k : in.kinds) out.add_kinds(static_cast<std::uint32_t>(k));
  for (const auto& r : in.regions) {
    out.add_regions(r);
    regions_used.insert(r);
  }
  out.mutable_boundary_particles()->Assign(in.boundary_particles.begin(),
                                           in.boundary_particles.end());
  out.mutable_boundary_areas()->Assign(in.boundary_areas.begin(), in.boundary_areas.end());
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
    auto* w = out.Add();
    w->set_region(p.region);
    for (int a = 0; a < 3; ++a) {
      w->add_point(p.point[a]);
      if (p.radius == 0) w->add_normal(p.normal[a]);
    }
    w->set_radius(p.radius);
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
  throw InvalidArgument("fluid.wall_model = '" + name + "' (allowed: stationary, morris)");
}

void to_proto(const OpenBoundarySettings& in, fluid::v1::OpenBoundary& out) {
  out.set_axis(static_cast<std::uint32_t>(in.axis));
  out.set_inlet_lo(in.inlet_lo);
  out.set_fluid_lo(in.fluid_lo);
  out.set_fluid_hi(in.fluid_hi);
  out.set_outlet_hi(in.outlet_hi);
  out.set_profile(in.parabolic ? fluid::v1::OpenBoundary::PROFILE_PARABOLIC
                               : fluid::v1::OpenBoundary::PROFILE_UNIFORM);
  out.set_mean_velocity(in.mean_velocity);
  out.set_cross_axis(static_cast<std::uint32_t>(in.cross_axis));
  out.set_wall_lo(in.wall_lo);
  out.set_wall_hi(in.wall_hi);
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
  if (f.open_boundary) to_proto(*f.open_boundary, *m->mutable_open_boundary());
  if (f.boussinesq) {
    m->set_buoyancy_species(f.boussinesq->species);
    m->set_buoyancy_coefficient(f.boussinesq->coefficient);
    m->set_buoyancy_reference(f.boussinesq->reference);
    for (double d : f.boussinesq->direction) m->add_buoyancy_direction(d);
  }
  std::set<std::string> regions_used;
  for (const auto& s : scene.species) {
    if (!contains(plan.fluid_species, s.name)) continue;
    to_proto(s, *m->add_species(), regions_used);
    if (!s.stochastic) {
      add_inflows(scene, s, *m);  // a stochastic species' buffer is held by ssa_service
      auto* c = init.mutable_concentrations()->add_species();
      c->set_name(s.name);
      c->mutable_concentrations()->Assign(s.initial.begin(), s.initial.end());
    }
  }
  for (const auto& r : scene.reactions) {
    if (!r.stochastic) to_proto(r, *m->add_reactions(), regions_used);
  }
  add_wall_planes(scene, *m->mutable_wall_planes(), regions_used);
  add_regions(scene, regions_used, m->mutable_regions());
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
  m->set_convention(scene.ssa.convention == JumpConvention::kSymmetric
                        ? ssa::v1::JUMP_CONVENTION_SYMMETRIC
                        : ssa::v1::JUMP_CONVENTION_VOLUME);
  m->set_seed(seed);
  std::set<std::string> regions_used;
  for (const auto& s : scene.species) {
    if (!s.stochastic || !contains(plan.ssa_species, s.name)) continue;
    to_proto(s, *m->add_species(), regions_used);
    add_inflows(scene, s, *m);
    auto* c = init.mutable_counts()->add_species();
    c->set_name(s.name);
    auto* counts = c->mutable_counts();
    counts->Reserve(static_cast<int>(s.initial.size()));
    for (double v : s.initial) counts->Add(static_cast<std::int64_t>(std::llround(v)));
  }
  for (const auto& r : scene.reactions) {
    if (r.stochastic) to_proto(r, *m->add_reactions(), regions_used);
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
  }
  add_regions(scene, regions_used, m->mutable_regions());
  wire::to_proto(particles, *init.mutable_particles(), /*with_velocities=*/false);
  return init;
}

}  // namespace sadr::orchestrator
