// SPDX-License-Identifier: MIT
#include "sadr/ssa/model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <set>
#include <string>
#include <utility>

#include "sadr/common/status.hpp"

namespace sadr::ssa {

Species::Species(std::string name, double diffusivity) {
  def.name = std::move(name);
  def.diffusivity = diffusivity;
}

Reaction::Reaction(std::string name, std::vector<std::pair<int, int>> reactants,
                   std::vector<std::pair<int, int>> products, double rate,
                   std::vector<ParticleKind> kinds, std::vector<std::uint32_t> voxels)
    : reactants(std::move(reactants)), products(std::move(products)), voxels(std::move(voxels)) {
  def.name = std::move(name);
  def.rate = rate;
  def.kinds = std::move(kinds);
}

namespace {

void check_species_ref(std::vector<std::string>& issues, const std::string& field, int s,
                       std::size_t n_species) {
  if (s < 0 || static_cast<std::size_t>(s) >= n_species) {
    issues.push_back(field + " = " + std::to_string(s) + " (allowed: 0.." +
                     std::to_string(static_cast<long>(n_species) - 1) + ")");
  }
}

}  // namespace

void Model::validate() const {
  std::vector<std::string> issues;
  model::Problems checks;  // the shared range checks (sadr/model/problems.hpp)
  const std::size_t ns = species.size();
  if (ns == 0) issues.emplace_back("species: empty (at least one species is required)");
  std::set<std::string> names;
  for (std::size_t k = 0; k < frozen_species.size(); ++k) {
    if (frozen_species[k].empty() || !names.insert(frozen_species[k]).second) {
      issues.push_back("frozen_species[" + std::to_string(k) + "] = '" + frozen_species[k] +
                       "' is empty or a duplicate");
    }
  }
  for (std::size_t s = 0; s < ns; ++s) {
    const std::string f = "species[" + std::to_string(s) + "]";
    if (species[s].def.name.empty()) issues.push_back(f + ".name is empty");
    if (!names.insert(species[s].def.name).second) {
      issues.push_back(f + ".name = '" + species[s].def.name + "' is a duplicate");
    }
    checks.finite_nonneg(f + ".diffusivity", species[s].def.diffusivity);
  }
  for (std::size_t r = 0; r < reactions.size(); ++r) {
    const Reaction& rx = reactions[r];
    const std::string f = "reactions[" + std::to_string(r) + "] '" + rx.def.name + "'";
    model::ReactionNumbers numbers;
    numbers.rate = rx.def.rate;
    numbers.has_law = rx.def.law.has_value();
    numbers.areas = &rx.def.boundary_areas;
    numbers.sites = rx.voxels.size();
    for (std::size_t k = 0; k < rx.reactants.size(); ++k) {
      const std::string fk = f + ".reactants[" + std::to_string(k) + "]";
      check_species_ref(issues, fk + ".species", rx.reactants[k].first, ns);
      numbers.reactant_counts.push_back(rx.reactants[k].second);
      for (std::size_t l = 0; l < k; ++l) {
        if (rx.reactants[l].first == rx.reactants[k].first) {
          issues.push_back(fk + ": species " + std::to_string(rx.reactants[k].first) +
                           " listed twice (give A + A as one entry with stoichiometry 2)");
        }
      }
    }
    for (std::size_t k = 0; k < rx.products.size(); ++k) {
      check_species_ref(issues, f + ".products[" + std::to_string(k) + "].species",
                        rx.products[k].first, ns);
      numbers.product_counts.push_back(rx.products[k].second);
    }
    model::Problems problems;
    problems.set_prefix(f);
    model::check(numbers, problems);
    for (const auto& p : problems.list()) issues.push_back(p.message());
    if (rx.def.law) {
      try {
        (void)rate_law::RateLaw(*rx.def.law, law_names());
      } catch (const InvalidArgument& e) {
        issues.push_back(f + ".law: " + e.what());
      }
    }
  }
  try {
    box.validate();
  } catch (const InvalidArgument& e) {
    issues.emplace_back(e.what());
  }
  if (!(std::isfinite(smoothing_length) && smoothing_length > 0)) {
    issues.push_back("smoothing_length = " + format_value(smoothing_length) +
                     " (allowed: finite and > 0)");
  } else if (box.dimension >= 1 && box.dimension <= 3) {
    for (int a = 0; a < box.dimension; ++a) {
      if (box.periodic[a] && !(2.0 * smoothing_length < box.length(a))) {
        issues.push_back("smoothing_length = " + format_value(smoothing_length) +
                         " must be < half the periodic box length " + format_value(box.length(a)) +
                         " on axis " + std::to_string(a));
      }
    }
  }
  checks.finite_nonneg("regularization", regularization);
  if (method == SsaMethod::kAdaptive && !(tolerance > 0 && tolerance < 1)) {
    issues.push_back("tolerance = " + format_value(tolerance) + " (allowed: 0 < tolerance < 1)");
  }
  for (std::size_t k = 0; k < reservoirs.size(); ++k) {
    const std::string f = "reservoirs[" + std::to_string(k) + "]";
    check_species_ref(issues, f + ".species", reservoirs[k].species, ns);
    checks.finite_nonneg(f + ".concentration", reservoirs[k].concentration);
    for (std::size_t l = 0; l < k; ++l) {
      if (reservoirs[l].species == reservoirs[k].species && reservoirs[l].voxels.empty() &&
          reservoirs[k].voxels.empty()) {
        issues.push_back(f + ".species = " + std::to_string(reservoirs[k].species) +
                         " already has an all-walls reservoir (give 'voxels' to split walls)");
      }
    }
  }
  for (std::size_t k = 0; k < neumann.size(); ++k) {
    const std::string f = "neumann[" + std::to_string(k) + "]";
    check_species_ref(issues, f + ".species", neumann[k].species, ns);
    checks.finite_nonneg(f + ".flux", neumann[k].flux);
  }
  for (std::size_t k = 0; k < free_walls.size(); ++k) {
    const FreeWall& fw = free_walls[k];
    const std::string f = "free_walls[" + std::to_string(k) + "]";
    check_species_ref(issues, f + ".species", fw.species, ns);
    for (std::size_t l = 0; l < reservoirs.size(); ++l) {
      const WallReservoir& w = reservoirs[l];
      if (w.species != fw.species) continue;
      const std::string both =
          f + " and reservoirs[" + std::to_string(l) + "]: species " + std::to_string(fw.species);
      if (fw.voxels.empty() && w.voxels.empty()) {
        issues.push_back(both +
                         ": every wall particle is both free and a reservoir (list the voxels "
                         "of one of them)");
        continue;
      }
      for (std::uint32_t v : fw.voxels) {
        if (std::find(w.voxels.begin(), w.voxels.end(), v) != w.voxels.end()) {
          issues.push_back(both + ", voxel " + std::to_string(v) +
                           " is both a reservoir and free (allowed: one of them)");
        }
      }
    }
  }
  for (std::size_t k = 0; k < morris_walls.size(); ++k) {
    const std::string f = "morris_walls[" + std::to_string(k) + "]";
    const WallSurface& w = morris_walls[k].surface;
    if (morris_walls[k].voxels.empty()) issues.push_back(f + ".voxels: empty");
    if (!std::all_of(w.point.begin(), w.point.end(), [](double x) { return std::isfinite(x); })) {
      issues.push_back(f + ".surface.point: not finite");
    }
    if (!(std::isfinite(w.radius) && w.radius >= 0)) {
      issues.push_back(f + ".surface.radius = " + format_value(w.radius) +
                       " (allowed: 0 for a plane, or finite and > 0)");
    } else if (w.radius == 0) {
      const auto& n = w.inward_normal;
      const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      if (!(std::abs(len - 1.0) < 1e-9)) {
        issues.push_back(f + ".surface.inward_normal has length " + format_value(len) +
                         " (allowed: a unit vector)");
      }
    }
    if (!free_walls.empty()) {
      issues.push_back(f +
                       ": Morris walls together with free_walls are not supported (the "
                       "scaled edges would reach the free species too)");
    }
  }
  if (!morris_tangents.empty()) {
    for (auto& p : morris_tangents.problems(SIZE_MAX)) issues.push_back("morris_" + p);
    if (!morris_walls.empty()) {
      issues.push_back(
          "morris_tangents: not together with morris_walls (one wall surface per "
          "wall particle)");
    }
    if (!free_walls.empty()) {
      issues.push_back("morris_tangents: Morris walls together with free_walls are not supported");
    }
  }
  for (const auto& p : checks.list()) issues.push_back(p.message());
  if (issues.empty()) return;
  std::string msg = "invalid ssa model: ";
  for (std::size_t k = 0; k < issues.size(); ++k) msg += (k ? "; " : "") + issues[k];
  throw InvalidArgument(msg, {{"issues", std::to_string(issues.size())}});
}

int Model::species_index(std::string_view name) const {
  for (std::size_t s = 0; s < species.size(); ++s) {
    if (species[s].def.name == name) return static_cast<int>(s);
  }
  std::string known;
  for (std::size_t s = 0; s < species.size(); ++s) known += (s ? ", " : "") + species[s].def.name;
  throw InvalidArgument("unknown species name '" + std::string(name) + "' (known: " + known + ")",
                        {{"field", "species"}, {"value", std::string(name)}});
}

std::vector<std::string> Model::species_names() const {
  std::vector<std::string> out;
  for (const auto& s : species) out.push_back(s.def.name);
  return out;
}

std::vector<std::string> Model::law_names() const {
  std::vector<std::string> out = species_names();
  out.insert(out.end(), frozen_species.begin(), frozen_species.end());
  return out;
}

namespace {
struct Fnv {
  std::uint64_t h = 1469598103934665603ULL;
  void bytes(const void* p, std::size_t n) {
    const auto* c = static_cast<const unsigned char*>(p);
    for (std::size_t k = 0; k < n; ++k) h = (h ^ c[k]) * 1099511628211ULL;
  }
  template <typename T>
  void pod(const T& v) {
    bytes(&v, sizeof v);
  }
  void str(const std::string& s) {
    pod(s.size());
    bytes(s.data(), s.size());
  }
};
}  // namespace

std::uint64_t Model::fingerprint() const {
  Fnv f;
  f.pod(species.size());
  for (const auto& s : species) {
    f.str(s.def.name);
    f.pod(s.def.diffusivity);
  }
  f.pod(reactions.size());
  for (const auto& r : reactions) {
    f.str(r.def.name);
    for (const auto& [s, n] : r.reactants) f.pod(s), f.pod(n);
    f.pod(-1);
    for (const auto& [s, n] : r.products) f.pod(s), f.pod(n);
    f.pod(-1);
    f.pod(r.def.rate);
    if (r.def.law) {  // absent without a law: old fingerprints stay valid
      f.str(r.def.law->text());
      for (const auto& [name, value] : r.def.law->parameters) f.str(name), f.pod(value);
    }
    for (auto k : r.def.kinds) f.pod(k);
    f.pod(-1);
    for (auto v : r.voxels) f.pod(v);
    // absent without a boundary flux: old fingerprints stay valid
    if (!r.def.boundary_areas.empty()) {
      f.pod(-3);
      for (auto a : r.def.boundary_areas) f.pod(a);
    }
    f.pod(-1);
  }
  for (const auto& name : frozen_species) f.str(name);  // none: old fingerprints stay valid
  f.pod(box.dimension);
  f.pod(box.lo);
  f.pod(box.hi);
  f.pod(box.periodic);
  f.pod(smoothing_length);
  f.pod(regularization);
  f.pod(convention);
  for (const auto& w : reservoirs) {
    f.pod(w.species), f.pod(w.concentration);
    for (auto v : w.voxels) f.pod(v);
    f.pod(-1);
  }
  f.pod(-1);
  for (const auto& n : neumann) f.pod(n.species), f.pod(n.flux);
  if (!free_walls.empty()) {  // absent from the hash when unused: old fingerprints stay valid
    f.pod(-2);
    for (const auto& w : free_walls) {
      f.pod(w.species);
      for (auto v : w.voxels) f.pod(v);
      f.pod(-1);
    }
  }
  if (!morris_walls.empty()) {  // absent when unused: old fingerprints stay valid
    f.pod(-4);
    for (const auto& w : morris_walls) {
      for (auto v : w.voxels) f.pod(v);
      f.pod(-1);
      f.pod(w.surface.point);
      f.pod(w.surface.inward_normal);
      f.pod(w.surface.radius);
    }
  }
  if (!morris_tangents.empty()) {  // absent when unused: old fingerprints stay valid
    f.pod(-5);
    for (auto v : morris_tangents.particles) f.pod(v);
    for (auto v : morris_tangents.depths) f.pod(v);
    for (auto v : morris_tangents.normals) f.pod(v);
  }
  if (method == SsaMethod::kAdaptive) {  // absent for the exact NSM: old fingerprints stay valid
    f.pod(-6);
    f.pod(tolerance);
  }
  return f.h;
}

}  // namespace sadr::ssa
