// SPDX-License-Identifier: MIT
// sadr.fluid.v1.FluidModel -> sadr::fluid::FluidModel (validation at the boundary).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>

#include "sadr/fluid/fluid_service.hpp"
#include "sadr/wire/convert.hpp"
#include "sadr/wire/model_proto.hpp"

namespace sadr::fluid {
namespace {

std::array<double, 3> vec3(const google::protobuf::RepeatedField<double>& v,
                           const std::string& where, std::array<double, 3> fallback) {
  if (v.empty()) return fallback;
  if (v.size() != 3) {
    throw InvalidArgument(where + " needs 3 values, got " + std::to_string(v.size()));
  }
  return {v[0], v[1], v[2]};
}

WallCondition wall_condition(const model::SpeciesBoundary& w) {
  switch (w.condition) {
    case model::BoundaryCondition::kDirichlet:
      return {WallCondition::Type::kDirichlet, w.value};
    case model::BoundaryCondition::kNeumann:
      return {WallCondition::Type::kNeumann, w.value};
    case model::BoundaryCondition::kFree:
      return {WallCondition::Type::kFree, 0.0};
    default:
      return {WallCondition::Type::kNoFlux, 0.0};
  }
}

std::vector<std::pair<int, int>> stoichiometry(const std::vector<model::StoichiometryEntry>& side,
                                               const FluidModel& m, const std::string& where) {
  std::vector<std::pair<int, int>> out;
  for (std::size_t k = 0; k < side.size(); ++k) {
    const int s = m.species_index(side[k].species);
    const std::string here = where + "[" + std::to_string(k) + "]";
    if (s < 0 || !m.species[static_cast<std::size_t>(s)].deterministic()) {
      throw InvalidArgument(here + ".species = '" + side[k].species +
                            "' is not a deterministic species of this scene");
    }
    out.emplace_back(s, static_cast<int>(side[k].count));
  }
  return out;
}

/// The typed FluidModel.open_boundary (FluidModel::validate() checks the channel against the box
/// and h).
OpenBoundary open_boundary(const model::OpenBoundarySettings& in) {
  OpenBoundary ob;
  ob.enabled = true;
  ob.axis = in.axis;
  ob.inlet_lo = in.inlet_lo;
  ob.fluid_lo = in.fluid_lo;
  ob.fluid_hi = in.fluid_hi;
  ob.outlet_hi = in.outlet_hi;
  ob.profile = in.parabolic ? OpenBoundary::Profile::kParabolic : OpenBoundary::Profile::kUniform;
  ob.mean_velocity = in.mean_velocity;
  ob.cross_axis = in.cross_axis;
  ob.wall_lo = in.wall_lo;
  ob.wall_hi = in.wall_hi;
  return ob;
}

}  // namespace

FluidModel model_from_proto(const v1::FluidModel& in, std::size_t n_particles) {
  const std::string where = "init.model";
  FluidModel m;
  m.box = wire::from_proto(in.box(), where + ".box");
  m.smoothing_length = in.smoothing_length();
  if (!in.kernel().empty()) m.kernel = in.kernel();
  m.reference_density = in.reference_density();
  m.sound_speed = in.sound_speed();
  m.shear_viscosity = in.shear_viscosity();
  m.temperature = in.temperature();
  m.gravity = vec3(in.gravity(), where + ".gravity", {0, 0, 0});
  m.seed = in.seed();
  m.max_time_step = in.max_time_step();
  m.force_time_step = in.force_time_step();

  const auto regions = wire::regions_from_proto(in.regions(), n_particles, where);
  std::map<std::string, std::size_t, std::less<>> wall_region_index;
  // Morris walls: the planar surface of each named region of wall particles (before the species'
  // wall conditions, which may name the same regions).
  for (int w = 0; w < in.wall_planes_size(); ++w) {
    const auto& p = in.wall_planes(w);
    const std::string here = where + ".wall_planes[" + std::to_string(w) + "]";
    if (wall_region_index.count(p.region()) != 0) {
      throw InvalidArgument(here + ".region = '" + p.region() + "' has a plane already");
    }
    WallRegion region;
    region.name = p.region();
    region.particles = wire::region_particles(regions, p.region(), here);
    const WallSurface surface = wire::from_proto(p, here);
    region.surface_point = surface.point;
    region.inward_normal = surface.inward_normal;
    region.surface_radius = surface.radius;
    m.wall_regions.push_back(std::move(region));
    wall_region_index.emplace(p.region(), m.wall_regions.size() - 1);
  }
  // The model's own checks (the same the scene loader ran), then index resolution.
  model::Problems problems;
  for (int s = 0; s < in.species_size(); ++s) {
    const std::string at = where + ".species[" + std::to_string(s) + "]";
    const model::Species sp = wire::from_proto(in.species(s), at);
    problems.set_prefix(at);
    model::check(sp, problems);
    SpeciesSpec spec(sp);
    for (std::size_t w = 0; w < sp.boundaries.size(); ++w) {
      const model::SpeciesBoundary& wall = sp.boundaries[w];
      if (wall.region.empty()) {
        spec.default_wall = wall_condition(wall);
        continue;
      }
      const std::string here = at + ".walls[" + std::to_string(w) + "]";
      auto it = wall_region_index.find(wall.region);
      if (it == wall_region_index.end()) {
        WallRegion region;
        region.name = wall.region;
        region.particles = wire::region_particles(regions, wall.region, here);
        m.wall_regions.push_back(std::move(region));
        it = wall_region_index.emplace(wall.region, m.wall_regions.size() - 1).first;
      }
      spec.wall_conditions.resize(m.wall_regions.size(), spec.default_wall);
      spec.wall_conditions[it->second] = wall_condition(wall);
    }
    m.species.push_back(std::move(spec));
  }
  // Every species lists one condition per wall region (its default where unset).
  for (auto& spec : m.species)
    spec.wall_conditions.resize(m.wall_regions.size(), spec.default_wall);

  for (int r = 0; r < in.reactions_size(); ++r) {
    const std::string here = where + ".reactions[" + std::to_string(r) + "]";
    const model::Reaction rx = wire::from_proto(in.reactions(r), here);
    problems.set_prefix(here);
    model::check(rx, problems);
    ReactionSpec spec;
    spec.def = rx;
    for (const auto& name : rx.regions) {
      const auto& v = wire::region_particles(regions, name, here + ".regions");
      spec.particles.insert(spec.particles.end(), v.begin(), v.end());
    }
    std::sort(spec.particles.begin(), spec.particles.end());  // regions may overlap
    spec.particles.erase(std::unique(spec.particles.begin(), spec.particles.end()),
                         spec.particles.end());
    spec.reactants = stoichiometry(rx.reactants, m, here + ".reactants");
    spec.products = stoichiometry(rx.products, m, here + ".products");
    if (!rx.boundary_particles.empty()) spec.particles = rx.boundary_particles;
    m.reactions.push_back(std::move(spec));
  }
  problems.throw_if_any();

  switch (in.density_mode()) {
    case v1::DENSITY_MODE_CONTINUITY:
      m.density_mode = DensityMode::kContinuity;
      break;
    case v1::DENSITY_MODE_SUMMATION:
      m.density_mode = DensityMode::kSummation;
      break;
    default:
      throw InvalidArgument(where + ".density_mode = " + std::to_string(in.density_mode()) +
                            " (allowed: DENSITY_MODE_CONTINUITY, DENSITY_MODE_SUMMATION)");
  }
  switch (in.wall_model()) {
    case v1::WALL_MODEL_STATIONARY:
      m.wall_model = WallModel::kStationary;
      break;
    case v1::WALL_MODEL_MORRIS:
      m.wall_model = WallModel::kMorrisExtrapolated;
      break;
    case v1::WALL_MODEL_ADAMI:
      m.wall_model = WallModel::kAdami;
      break;
    default:
      throw InvalidArgument(where + ".wall_model = " + std::to_string(in.wall_model()) +
                            " (allowed: WALL_MODEL_STATIONARY, WALL_MODEL_MORRIS, "
                            "WALL_MODEL_ADAMI)");
  }
  if (in.has_wall_tangents()) {
    if (in.wall_planes_size() != 0) {
      throw InvalidArgument(where + ".wall_tangents: not together with wall_planes");
    }
    m.wall_tangents = wire::from_proto(in.wall_tangents(), n_particles, where + ".wall_tangents");
  }
  if (m.wall_model == WallModel::kMorrisExtrapolated && in.wall_planes_size() == 0 &&
      m.wall_tangents.empty()) {
    throw InvalidArgument(where +
                          ".wall_model = WALL_MODEL_MORRIS needs wall_planes (the wall "
                          "surface of each region of wall particles) or wall_tangents");
  }
  if (in.has_open_boundary()) {
    m.open_boundary = open_boundary(wire::from_proto(in.open_boundary(), where + ".open_boundary"));
  }
  for (const auto& [key, path] : in.files()) m.backend_files[key] = path;
  for (const auto& [key, value] : in.parameters()) {
    if (key == "density_diffusion") {
      m.density_diffusion = value;
    } else if (key == "diffusion_eps") {
      m.diffusion_eps = value;
    } else if (key == "density_band") {
      m.density_band = value;
    } else if (key == "neighbor_skin") {
      m.neighbor_skin = value;
    } else {
      m.backend_parameters[key] = value;  // the backend checks the name
    }
  }
  if (!in.buoyancy_species().empty()) {
    m.boussinesq.species = m.species_index(in.buoyancy_species());
    if (m.boussinesq.species < 0) {
      throw InvalidArgument(where + ".buoyancy_species = '" + in.buoyancy_species() +
                            "' is not a species of this scene");
    }
    m.boussinesq.coefficient = in.buoyancy_coefficient();
    m.boussinesq.reference = in.buoyancy_reference();
    m.boussinesq.direction =
        vec3(in.buoyancy_direction(), where + ".buoyancy_direction", {0, 1, 0});
  }
  for (int k = 0; k < in.body_forces_size(); ++k) {  // the regions of the bodies' wall particles
    const std::string here = where + ".body_forces[" + std::to_string(k) + "]";
    m.body_forces.push_back(
        {in.body_forces(k), wire::region_particles(regions, in.body_forces(k), here)});
  }
  for (int k = 0; k < in.regions_size(); ++k) {  // solid bodies whose wall particles move
    const auto& r = in.regions(k);
    if (!r.has_motion()) continue;
    const std::string here = where + ".regions[" + std::to_string(k) + "].motion";
    MovingBody body;
    body.name = r.name();
    body.particles = wire::region_particles(regions, r.name(), here);
    body.motion.velocity = vec3(r.motion().velocity(), here + ".velocity", {0, 0, 0});
    body.motion.angular_velocity = r.motion().angular_velocity();
    body.motion.center = vec3(r.motion().center(), here + ".center", {0, 0, 0});
    body.motion.axis = vec3(r.motion().axis(), here + ".axis", {0, 0, 1});
    m.moving_bodies.push_back(std::move(body));
  }
  m.validate();
  return m;
}

BackendStart start_from_proto(const v1::InitRequest& req) {
  BackendStart start;
  start.particles = wire::from_proto(req.particles(), "init.particles");
  const ParticleState& particles = start.particles;
  start.model = model_from_proto(req.model(), particles.size());
  const FluidModel& model = start.model;
  std::vector<std::vector<double>>& conc = start.concentrations;
  conc.resize(model.species.size());
  for (int k = 0; k < req.concentrations().species_size(); ++k) {
    const auto& f = req.concentrations().species(k);
    const std::string where = "init.concentrations.species[" + std::to_string(k) + "]";
    const int s = model.species_index(f.name());
    if (s < 0) throw InvalidArgument(where + ": unknown species '" + f.name() + "'");
    if (static_cast<std::size_t>(f.concentrations_size()) != particles.size()) {
      throw InvalidArgument(where + ".concentrations has " +
                            std::to_string(f.concentrations_size()) + " entries, expected " +
                            std::to_string(particles.size()));
    }
    conc[static_cast<std::size_t>(s)].assign(f.concentrations().begin(), f.concentrations().end());
  }
  for (auto& c : conc) {
    if (c.empty()) c.assign(particles.size(), 0.0);
  }
  for (int k = 0; k < req.model().inflows_size(); ++k) {
    const std::string where = "init.model.inflows[" + std::to_string(k) + "]";
    const auto& in = req.model().inflows(k);
    const int s = model.species_index(in.species());
    if (s < 0) {
      throw InvalidArgument(
          where + ".species = '" + in.species() + "' is not a deterministic species of the model",
          {{"field", where + ".species"}, {"value", in.species()}});
    }
    start.inflows.push_back({s, wire::from_proto(in, particles.dimension, where)});
  }
  return start;
}

}  // namespace sadr::fluid
