// SPDX-License-Identifier: MIT
// The model's types <-> sadr.common.v1 / fluid.v1 / ssa.v1 messages.
#include "sadr/wire/model_proto.hpp"

#include <string>

#include "sadr/common/status.hpp"
#include "sadr/wire/convert.hpp"

namespace sadr::wire {

common::v1::WallCondition to_proto(model::BoundaryCondition condition) {
  switch (condition) {
    case model::BoundaryCondition::kDirichlet:
      return common::v1::WALL_CONDITION_DIRICHLET;
    case model::BoundaryCondition::kNeumann:
      return common::v1::WALL_CONDITION_NEUMANN;
    case model::BoundaryCondition::kFree:
      return common::v1::WALL_CONDITION_FREE;
    case model::BoundaryCondition::kNone:
    case model::BoundaryCondition::kInflow:
      break;
  }
  return common::v1::WALL_CONDITION_NONE;
}

model::BoundaryCondition from_proto(common::v1::WallCondition condition) {
  switch (condition) {
    case common::v1::WALL_CONDITION_DIRICHLET:
      return model::BoundaryCondition::kDirichlet;
    case common::v1::WALL_CONDITION_NEUMANN:
      return model::BoundaryCondition::kNeumann;
    case common::v1::WALL_CONDITION_FREE:
      return model::BoundaryCondition::kFree;
    default:
      return model::BoundaryCondition::kNone;
  }
}

void to_proto(const model::Species& in, common::v1::Species& out) {
  out.set_name(in.name);
  out.set_stochastic(in.stochastic);
  out.set_diffusivity(in.diffusivity);
  for (const auto& b : in.boundaries) {
    if (b.condition == model::BoundaryCondition::kInflow) continue;
    auto* w = out.add_walls();
    w->set_region(b.region);
    w->set_condition(to_proto(b.condition));
    w->set_value(b.value);
  }
}

model::Species from_proto(const common::v1::Species& in, std::string_view /*where*/) {
  model::Species s;
  s.name = in.name();
  s.stochastic = in.stochastic();
  s.diffusivity = in.diffusivity();
  for (const auto& w : in.walls()) {
    s.boundaries.push_back(
        model::SpeciesBoundary{w.region(), from_proto(w.condition()), w.value()});
  }
  return s;
}

void to_proto(const model::Reaction& in, common::v1::Reaction& out) {
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
  if (in.law) to_proto(*in.law, *out.mutable_law());
  for (auto k : in.kinds) out.add_kinds(static_cast<std::uint32_t>(k));
  for (const auto& r : in.regions) out.add_regions(r);
  out.mutable_boundary_particles()->Assign(in.boundary_particles.begin(),
                                           in.boundary_particles.end());
  out.mutable_boundary_areas()->Assign(in.boundary_areas.begin(), in.boundary_areas.end());
}

model::Reaction from_proto(const common::v1::Reaction& in, std::string_view where) {
  const std::string here(where);
  model::Reaction r;
  r.name = in.name();
  for (const auto& e : in.reactants()) r.reactants.push_back({e.species(), e.count()});
  for (const auto& e : in.products()) r.products.push_back({e.species(), e.count()});
  r.rate = in.rate();
  if (in.has_law()) r.law = from_proto(in.law(), here + ".law");
  for (int k = 0; k < in.kinds_size(); ++k) {
    if (in.kinds(k) > 3) {
      throw InvalidArgument(here + ".kinds[" + std::to_string(k) +
                            "] = " + std::to_string(in.kinds(k)) + " (allowed: 0..3)");
    }
    r.kinds.push_back(static_cast<ParticleKind>(in.kinds(k)));
  }
  r.regions.assign(in.regions().begin(), in.regions().end());
  boundary_flux_sites(in, here, r.boundary_particles, r.boundary_areas);
  return r;
}

ssa::v1::JumpConvention to_proto(model::JumpConvention convention) {
  return convention == model::JumpConvention::kSymmetric ? ssa::v1::JUMP_CONVENTION_SYMMETRIC
                                                         : ssa::v1::JUMP_CONVENTION_VOLUME;
}

model::JumpConvention from_proto(ssa::v1::JumpConvention convention,
                                 model::JumpConvention fallback) {
  switch (convention) {
    case ssa::v1::JUMP_CONVENTION_SYMMETRIC:
      return model::JumpConvention::kSymmetric;
    case ssa::v1::JUMP_CONVENTION_VOLUME:
      return model::JumpConvention::kVolume;
    default:
      return fallback;
  }
}

void to_proto(const model::WallPlane& in, common::v1::WallPlane& out) {
  out.set_region(in.region);
  for (int a = 0; a < 3; ++a) {
    out.add_point(in.point[a]);
    if (in.radius == 0) out.add_normal(in.normal[a]);
  }
  out.set_radius(in.radius);
}

void to_proto(const model::OpenBoundarySettings& in, fluid::v1::OpenBoundary& out) {
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

model::OpenBoundarySettings from_proto(const fluid::v1::OpenBoundary& in, std::string_view where) {
  const std::string here(where);
  auto axis = [&](std::uint32_t v, const char* field) {
    if (v > 2) {
      throw InvalidArgument(here + "." + field + " = " + std::to_string(v) + " (allowed: 0, 1, 2)");
    }
    return static_cast<int>(v);
  };
  model::OpenBoundarySettings ob;
  ob.axis = axis(in.axis(), "axis");
  ob.inlet_lo = in.inlet_lo();
  ob.fluid_lo = in.fluid_lo();
  ob.fluid_hi = in.fluid_hi();
  ob.outlet_hi = in.outlet_hi();
  switch (in.profile()) {
    case fluid::v1::OpenBoundary::PROFILE_UNIFORM:
      ob.parabolic = false;
      break;
    case fluid::v1::OpenBoundary::PROFILE_PARABOLIC:
      ob.parabolic = true;
      break;
    default:
      throw InvalidArgument(here + ".profile = " + std::to_string(in.profile()) +
                            " (allowed: PROFILE_UNIFORM, PROFILE_PARABOLIC)");
  }
  ob.mean_velocity = in.mean_velocity();
  ob.cross_axis = axis(in.cross_axis(), "cross_axis");
  ob.wall_lo = in.wall_lo();
  ob.wall_hi = in.wall_hi();
  return ob;
}

}  // namespace sadr::wire
