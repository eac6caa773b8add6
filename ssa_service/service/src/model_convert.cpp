// SPDX-License-Identifier: MIT
// sadr.ssa.v1.SsaModel -> sadr::ssa::Model (validation at the process boundary).
#include <algorithm>
#include <map>
#include <string>

#include "sadr/ssa/ssa_service.hpp"
#include "sadr/wire/convert.hpp"

namespace sadr::ssa {
namespace {

std::vector<std::pair<int, int>> stoichiometry(
    const google::protobuf::RepeatedPtrField<common::v1::StoichiometryEntry>& entries,
    const std::map<std::string, int, std::less<>>& index, const std::string& where) {
  std::vector<std::pair<int, int>> out;
  for (int k = 0; k < entries.size(); ++k) {
    const auto& e = entries.Get(k);
    const auto it = index.find(e.species());
    if (it == index.end()) {
      std::string known;
      for (const auto& [name, i] : index) known += (known.empty() ? "" : ", ") + name;
      throw InvalidArgument(where + "[" + std::to_string(k) + "].species = '" + e.species() +
                            "' is not a stochastic species (known: " + known + ")");
    }
    if (e.count() < 1) {
      throw InvalidArgument(where + "[" + std::to_string(k) +
                            "].count = " + std::to_string(e.count()) + " (allowed: >= 1)");
    }
    out.emplace_back(it->second, static_cast<int>(e.count()));
  }
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
  switch (in.convention()) {
    case v1::JUMP_CONVENTION_SYMMETRIC:
      m.convention = JumpConvention::kSymmetric;
      break;
    case v1::JUMP_CONVENTION_VOLUME:
      m.convention = JumpConvention::kVolume;
      break;
    default:
      break;  // keep the core's default
  }
  const auto regions = wire::regions_from_proto(in.regions(), n_particles, where);

  std::map<std::string, int, std::less<>> index;
  species_names.clear();
  for (int s = 0; s < in.species_size(); ++s) {
    const auto& sp = in.species(s);
    if (!sp.stochastic()) continue;
    const int idx = static_cast<int>(m.species.size());
    index.emplace(sp.name(), idx);
    species_names.push_back(sp.name());
    m.species.push_back(Species{sp.name(), sp.diffusivity()});
    for (int w = 0; w < sp.walls_size(); ++w) {
      const auto& wall = sp.walls(w);
      const std::string here =
          where + ".species[" + std::to_string(s) + "].walls[" + std::to_string(w) + "]";
      std::vector<std::uint32_t> voxels;
      if (!wall.region().empty()) voxels = wire::region_particles(regions, wall.region(), here);
      switch (wall.condition()) {
        case common::v1::WALL_CONDITION_DIRICHLET:
          m.reservoirs.push_back(WallReservoir{idx, wall.value(), std::move(voxels)});
          break;
        case common::v1::WALL_CONDITION_NEUMANN:
          if (!wall.region().empty()) {
            throw InvalidArgument(here + ": a Neumann flux on region '" + wall.region() +
                                  "' is not supported by ssa_service (it applies to all walls; "
                                  "use region '')");
          }
          m.neumann.push_back(NeumannSource{idx, wall.value()});
          break;
        case common::v1::WALL_CONDITION_FREE:
          m.free_walls.push_back(FreeWall{idx, std::move(voxels)});
          break;
        default:
          break;  // no-flux
      }
    }
  }
  for (int r = 0; r < in.reactions_size(); ++r) {
    const auto& rx = in.reactions(r);
    const std::string here = where + ".reactions[" + std::to_string(r) + "]";
    Reaction out;
    out.name = rx.name().empty() ? "reaction " + std::to_string(r) : rx.name();
    out.reactants = stoichiometry(rx.reactants(), index, here + ".reactants");
    out.products = stoichiometry(rx.products(), index, here + ".products");
    out.rate = rx.rate();
    if (rx.has_law()) out.law = wire::from_proto(rx.law(), here + ".law");
    for (int k = 0; k < rx.kinds_size(); ++k) {
      if (rx.kinds(k) > 3) {
        throw InvalidArgument(here + ".kinds[" + std::to_string(k) +
                              "] = " + std::to_string(rx.kinds(k)) + " (allowed: 0..3)");
      }
      out.kinds.push_back(static_cast<ParticleKind>(rx.kinds(k)));
    }
    for (const auto& name : rx.regions()) {
      const auto& v = wire::region_particles(regions, name, here + ".regions");
      out.voxels.insert(out.voxels.end(), v.begin(), v.end());
    }
    std::sort(out.voxels.begin(), out.voxels.end());  // regions may overlap
    out.voxels.erase(std::unique(out.voxels.begin(), out.voxels.end()), out.voxels.end());
    wire::boundary_flux_sites(rx, here, out.voxels, out.areas);
    m.reactions.push_back(std::move(out));
  }
  for (int w = 0; w < in.wall_planes_size(); ++w) {
    const auto& p = in.wall_planes(w);
    const std::string here = where + ".wall_planes[" + std::to_string(w) + "]";
    m.morris_walls.push_back(
        MorrisWall{wire::region_particles(regions, p.region(), here), wire::from_proto(p, here)});
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
