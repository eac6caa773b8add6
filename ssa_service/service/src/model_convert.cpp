// SPDX-License-Identifier: MIT
// sadr.ssa.v1.SsaModel -> sadr::ssa::Model (validation at the process boundary).
#include <algorithm>
#include <map>
#include <string>

#include "sadr/ssa/ssa_service.hpp"
#include "sadr/wire/convert.hpp"
#include "sadr/wire/model_proto.hpp"

namespace sadr::ssa {
namespace {

/// Species names -> indices (what the model's names compile to).
using SpeciesIndex = std::map<std::string, int, std::less<>>;

std::vector<std::pair<int, int>> stoichiometry(const std::vector<model::StoichiometryEntry>& side,
                                               const SpeciesIndex& index,
                                               const std::string& where) {
  std::vector<std::pair<int, int>> out;
  for (std::size_t k = 0; k < side.size(); ++k) {
    const auto it = index.find(side[k].species);
    if (it == index.end()) {
      std::string known;
      for (const auto& [name, i] : index) known += (known.empty() ? "" : ", ") + name;
      throw InvalidArgument(where + "[" + std::to_string(k) + "].species = '" + side[k].species +
                            "' is not a stochastic species (known: " + known + ")");
    }
    out.emplace_back(it->second, static_cast<int>(side[k].count));
  }
  return out;
}

/// A species' wall conditions as reservoirs, Neumann sources and free walls of index `idx`.
void compile_walls(const model::Species& sp, int idx, const wire::RegionMap& regions,
                   const std::string& where, Model& m) {
  for (std::size_t w = 0; w < sp.boundaries.size(); ++w) {
    const model::SpeciesBoundary& wall = sp.boundaries[w];
    const std::string here = where + ".walls[" + std::to_string(w) + "]";
    std::vector<std::uint32_t> voxels;
    if (!wall.region.empty()) voxels = wire::region_particles(regions, wall.region, here);
    switch (wall.condition) {
      case model::BoundaryCondition::kDirichlet:
        m.reservoirs.push_back(WallReservoir{idx, wall.value, std::move(voxels)});
        break;
      case model::BoundaryCondition::kNeumann:
        if (!wall.region.empty()) {
          throw InvalidArgument(here + ": a Neumann flux on region '" + wall.region +
                                "' is not supported by ssa_service (it applies to all walls; "
                                "use region '')");
        }
        m.neumann.push_back(NeumannSource{idx, wall.value});
        break;
      case model::BoundaryCondition::kFree:
        m.free_walls.push_back(FreeWall{idx, std::move(voxels)});
        break;
      default:
        break;  // no-flux
    }
  }
}

/// One reaction by name as the core's indexed reaction: the model's reaction itself (unnamed:
/// "reaction <r>") with its species resolved to indices and its regions to voxels.
Reaction compile_reaction(const model::Reaction& rx, std::size_t r, const SpeciesIndex& index,
                          const wire::RegionMap& regions, const std::string& here) {
  Reaction out;
  out.def = rx;
  if (out.def.name.empty()) out.def.name = "reaction " + std::to_string(r);
  out.reactants = stoichiometry(rx.reactants, index, here + ".reactants");
  out.products = stoichiometry(rx.products, index, here + ".products");
  for (const auto& name : rx.regions) {
    const auto& v = wire::region_particles(regions, name, here + ".regions");
    out.voxels.insert(out.voxels.end(), v.begin(), v.end());
  }
  std::sort(out.voxels.begin(), out.voxels.end());  // regions may overlap
  out.voxels.erase(std::unique(out.voxels.begin(), out.voxels.end()), out.voxels.end());
  if (!rx.boundary_particles.empty()) out.voxels = rx.boundary_particles;
  return out;
}

}  // namespace

Model model_from_proto(const v1::SsaModel& in, std::size_t n_particles,
                       std::vector<std::string>& species_names) {
  const std::string where = "init.model";
  Model m;
  m.box = wire::from_proto(in.box(), where + ".box");
  m.smoothing_length = in.smoothing_length();
  if (in.has_regularization()) m.regularization = in.regularization();
  m.convention = wire::from_proto(in.convention(), m.convention);
  if (in.method() == v1::SSA_METHOD_ADAPTIVE) m.method = SsaMethod::kAdaptive;
  if (in.has_tolerance()) m.tolerance = in.tolerance();
  const auto regions = wire::regions_from_proto(in.regions(), n_particles, where);

  // The model's own checks first (the same the scene loader ran), then index resolution.
  model::Problems problems;
  SpeciesIndex index;
  species_names.clear();
  for (int s = 0; s < in.species_size(); ++s) {
    if (!in.species(s).stochastic()) continue;
    const std::string here = where + ".species[" + std::to_string(s) + "]";
    const model::Species sp = wire::from_proto(in.species(s), here);
    problems.set_prefix(here);
    model::check(sp, problems);
    const int idx = static_cast<int>(m.species.size());
    index.emplace(sp.name, idx);
    species_names.push_back(sp.name);
    m.species.push_back(Species{sp});
    compile_walls(sp, idx, regions, here, m);
  }
  for (int r = 0; r < in.reactions_size(); ++r) {
    const std::string here = where + ".reactions[" + std::to_string(r) + "]";
    const model::Reaction rx = wire::from_proto(in.reactions(r), here);
    problems.set_prefix(here);
    model::check(rx, problems);
    m.reactions.push_back(compile_reaction(rx, static_cast<std::size_t>(r), index, regions, here));
  }
  problems.throw_if_any();
  for (int w = 0; w < in.wall_planes_size(); ++w) {
    const auto& p = in.wall_planes(w);
    const std::string here = where + ".wall_planes[" + std::to_string(w) + "]";
    m.morris_walls.push_back(
        MorrisWall{wire::region_particles(regions, p.region(), here), wire::from_proto(p, here)});
  }
  if (in.has_wall_tangents()) {
    m.morris_tangents = wire::from_proto(in.wall_tangents(), n_particles, where + ".wall_tangents");
  }
  m.frozen_species.assign(in.frozen_species().begin(), in.frozen_species().end());
  m.validate();
  return m;
}

std::vector<InflowBuffer> inflows_from_proto(const v1::SsaModel& model, int dimension,
                                             const std::vector<std::string>& species_names) {
  std::vector<InflowBuffer> out;
  for (int k = 0; k < model.inflows_size(); ++k) {
    const auto& in = model.inflows(k);
    const std::string where = "init.model.inflows[" + std::to_string(k) + "]";
    InflowBuffer b;
    b.species = -1;
    for (std::size_t s = 0; s < species_names.size(); ++s) {
      if (species_names[s] == in.species()) b.species = static_cast<int>(s);
    }
    if (b.species < 0) {
      throw InvalidArgument(
          where + ".species = '" + in.species() + "' is not a stochastic species of the model",
          {{"field", where + ".species"}, {"value", in.species()}});
    }
    b.box = wire::from_proto(in, dimension, where);
    out.push_back(b);
  }
  return out;
}

void keep_non_fluid_wall_voxels(Model& model, const ParticleState& particles) {
  auto keep = [&](const char* what, std::size_t k, std::vector<std::uint32_t>& voxels) {
    if (voxels.empty()) return;  // every wall
    particles.validate();        // array lengths, before kind() is used
    std::vector<std::uint32_t> kept;
    kept.reserve(voxels.size());
    for (const std::uint32_t v : voxels) {
      if (v >= particles.size() || particles.kind(v) != ParticleKind::kFluid) kept.push_back(v);
    }
    if (kept.empty()) {
      throw InvalidArgument(std::string(what) + "[" + std::to_string(k) + "]: its " +
                            std::to_string(voxels.size()) +
                            " particles are all fluid particles; a wall condition applies to "
                            "the non-fluid particles of its region");
    }
    voxels = std::move(kept);
  };
  for (std::size_t k = 0; k < model.reservoirs.size(); ++k) {
    keep("reservoirs", k, model.reservoirs[k].voxels);
  }
  for (std::size_t k = 0; k < model.free_walls.size(); ++k) {
    keep("free_walls", k, model.free_walls[k].voxels);
  }
}

}  // namespace sadr::ssa
