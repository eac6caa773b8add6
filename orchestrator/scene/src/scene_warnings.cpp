// SPDX-License-Identifier: MIT
/// \file scene_warnings.cpp
/// Scenes that are valid but give a silent zero: a term that selects no particle, molecules
/// that can never move, a species nothing produces. Each is reported as a warning with the
/// key and line (Diagnostics::warning); `sadr validate` prints them and `--strict` refuses.
#include <algorithm>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "sadr/fluid/backend_schema.hpp"
#include "scene_parts.hpp"

namespace sadr::orchestrator::detail {
namespace {

std::string kinds_text(const std::vector<ParticleKind>& kinds) {
  std::string s = "[";
  for (std::size_t k = 0; k < kinds.size(); ++k) {
    if (k > 0) s += ", ";
    s += to_string(kinds[k]);
  }
  return s + "]";
}

bool has_kind(const std::vector<ParticleKind>& kinds, ParticleKind k) {
  return std::find(kinds.begin(), kinds.end(), k) != kinds.end();
}

/// The species field of the list entry named `name`, if any.
std::optional<Field> species_entry(const Field& root, const std::string& name) {
  const Field list = YamlReader::child(root, "species");
  if (!list.node.IsSequence()) return std::nullopt;
  for (std::size_t k = 0; k < list.node.size(); ++k) {
    const Field f = YamlReader::element(list, k);
    const Field n = YamlReader::child(f, "name");
    if (n.node.IsScalar() && n.node.Scalar() == name) return f;
  }
  return std::nullopt;
}

}  // namespace

void warn_reaction_selects_nothing(SceneContext& ctx, const Field& f, const Reaction& rx) {
  if (!ctx.particles_ok || !rx.boundary_particles.empty()) return;
  const ParticleState& p = ctx.scene.particles;
  std::set<ParticleKind> other;  // kinds the regions hold that `kinds` leaves out
  auto select = [&](std::uint32_t i) {
    if (has_kind(rx.kinds, p.kind(i))) return true;
    other.insert(p.kind(i));
    return false;
  };
  bool any = false;
  if (rx.regions.empty()) {
    for (std::size_t i = 0; i < p.size() && !any; ++i) any = select(static_cast<std::uint32_t>(i));
  } else {
    for (const auto& name : rx.regions) {
      const Region* rg = ctx.scene.find_region(name);
      if (rg == nullptr) continue;
      for (const std::uint32_t i : rg->particles) {
        if ((any = select(i))) break;
      }
      if (any) break;
    }
  }
  if (any) return;
  std::string msg = "reaction '" + rx.name + "' selects no particle: ";
  msg += rx.regions.empty() ? std::string("the scene") : "its regions";
  msg += " hold no particle of kinds " + kinds_text(rx.kinds) + ", so it never fires";
  if (!other.empty()) {
    std::vector<ParticleKind> held(other.begin(), other.end());
    msg += "; the particles there are of kinds " + kinds_text(held) + ": add them to `kinds`" +
           (has_kind(held, ParticleKind::kWall)
                ? " (and give its species `condition: free` on those wall particles)"
                : "");
  }
  ctx.reader.warning(
      YamlReader::present(YamlReader::child(f, "kinds")) ? YamlReader::child(f, "kinds") : f, msg);
}

void warn_inert_wall_molecules(SceneContext& ctx, const Field& f, const Species& sp) {
  if (!ctx.particles_ok || sp.initial.empty()) return;
  const ParticleState& p = ctx.scene.particles;
  std::vector<char> has_condition(p.size(), 0);
  for (const auto& b : sp.boundaries) {
    if (const Region* rg = ctx.scene.find_region(b.region)) {
      for (const std::uint32_t i : rg->particles) has_condition[i] = 1;
    }
  }
  // Only when nothing else starts the species: molecules beside others on inert walls are
  // inert, not a silent zero.
  double amount = 0;
  std::size_t particles = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (sp.initial[i] == 0.0) continue;
    if (p.kind(i) != ParticleKind::kWall || has_condition[i]) return;
    amount += sp.stochastic ? sp.initial[i] : sp.initial[i] * p.volume(i);
    ++particles;
  }
  if (particles == 0) return;
  ctx.reader.warning(
      YamlReader::child(f, "initial"),
      "all " + format_number(amount) + " molecules of '" + sp.name + "' start on " +
          std::to_string(particles) +
          " wall particle(s) without a boundary condition for it: wall particles take no part "
          "for such a species (condition none, the default), so these molecules never reach the "
          "fluid nor react; give their region `condition: free` in `boundaries` to let them "
          "exchange with the fluid, or start them in fluid particles");
}

void warn_absorbing_walls(SceneContext& ctx, const Field& f, const Species& sp) {
  if (!ctx.particles_ok || !sp.stochastic || !(sp.diffusivity > 0)) return;
  const ParticleState& p = ctx.scene.particles;
  std::vector<char> held(p.size(), 0);  // a dirichlet or free condition for this species
  bool dirichlet = false;
  for (const auto& b : sp.boundaries) {
    const bool d = b.condition == BoundaryCondition::kDirichlet;
    dirichlet = dirichlet || d;
    if (!d && b.condition != BoundaryCondition::kFree) continue;
    if (b.region.empty()) return;  // every wall particle
    if (const Region* rg = ctx.scene.find_region(b.region)) {
      for (const std::uint32_t i : rg->particles) held[i] = 1;
    }
  }
  if (!dirichlet) return;
  std::size_t open = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kind(i) == ParticleKind::kWall && !held[i]) ++open;
  }
  if (open == 0) return;
  ctx.reader.warning(
      YamlReader::child(f, "boundaries"),
      std::to_string(open) + " wall particle(s) have no `dirichlet` or `free` condition for '" +
          sp.name +
          "', a stochastic species with a `dirichlet` boundary: in the SSA they are reservoirs "
          "at C = 0 and absorb every molecule that reaches them, not the no-flux of `condition: "
          "none`; give them `condition: free` to close them (they then hold and pass on "
          "molecules like membrane particles), or `dirichlet` with value 0 to keep them "
          "absorbing (docs/ssa-core.md, \"Boundaries\")");
}

void warn_rounds_to_zero(SceneContext& ctx, const Field& value_field, const Species& sp,
                         const Region& rg, double concentration) {
  if (!sp.stochastic || concentration <= 0.0 || rg.particles.empty()) return;
  const ParticleState& p = ctx.scene.particles;
  double largest_volume = 0;
  for (const std::uint32_t i : rg.particles) {
    if (sp.initial[i] != 0.0) return;
    largest_volume = std::max(largest_volume, p.volume(i));
  }
  ctx.reader.warning(value_field,
                     "concentration " + format_number(concentration) + " gives 0 molecules in " +
                         "every particle of region '" + rg.name + "' (C V < 0.5 with V <= " +
                         format_number(largest_volume) + "): a stochastic species holds whole " +
                         "molecules, rounded per particle; raise the concentration or give a " +
                         "`count` per particle");
}

void warn_species_never_present(SceneContext& ctx, const Field& root) {
  const Scene& s = ctx.scene;
  if (!ctx.particles_ok) return;
  for (const Species& sp : s.species) {
    const auto found = species_entry(root, sp.name);
    if (!found) continue;
    const Field& entry = *found;
    bool dirichlet = false;
    for (const auto& b : sp.boundaries) {
      dirichlet = dirichlet || b.condition == BoundaryCondition::kDirichlet;
    }
    if (dirichlet && sp.diffusivity == 0.0) {
      ctx.reader.warning(YamlReader::child(entry, "diffusivity"),
                         "'" + sp.name + "' has a dirichlet boundary but diffusivity 0: " +
                             "nothing leaves its reservoir, so the boundary changes nothing " +
                             "outside its own particles");
    }
    const bool initial =
        std::any_of(sp.initial.begin(), sp.initial.end(), [](double v) { return v != 0.0; });
    const bool source = std::any_of(sp.boundaries.begin(), sp.boundaries.end(), [](const auto& b) {
      return b.condition != BoundaryCondition::kNone && b.condition != BoundaryCondition::kFree &&
             b.value != 0.0;
    });
    std::vector<std::string> consumers;
    bool produced = false;
    for (const Reaction& rx : s.reactions) {
      for (const auto& e : rx.products) produced = produced || e.species == sp.name;
      for (const auto& e : rx.reactants) {
        if (e.species == sp.name) consumers.push_back(rx.name);
      }
    }
    if (initial || source || produced) continue;
    std::string msg = "'" + sp.name +
                      "' is zero everywhere at t = 0 and nothing produces it (no reaction, "
                      "boundary value or boundary flux): it stays zero";
    if (!consumers.empty()) {
      msg += ", and the reaction(s) that consume it never fire (";
      for (std::size_t k = 0; k < consumers.size(); ++k) msg += (k ? ", " : "") + consumers[k];
      msg += ")";
    }
    ctx.reader.warning(YamlReader::child(entry, "name"), msg);
  }
}

void warn_empty_observables(SceneContext& ctx, const Field& root) {
  const Scene& s = ctx.scene;
  const auto* backend = fluid::schema::find(s.fluid.backend);
  if (!ctx.particles_ok || backend == nullptr || backend->capabilities.moves_particles) return;
  // Called only on a scene read without errors: observable k is list element k.
  const Field list = YamlReader::child(YamlReader::child(root, "output"), "observables");
  if (!list.node.IsSequence() || list.node.size() != s.output.observables.size()) return;
  for (std::size_t k = 0; k < s.output.observables.size(); ++k) {
    const ObservableSpec& o = s.output.observables[k];
    const Region* rg = s.find_region(o.region);
    if (rg == nullptr || !rg->particles.empty()) continue;
    ctx.reader.warning(YamlReader::element(list, k),
                       "observable '" + o.name + "' is over region '" + o.region +
                           "', which holds no particle, and the '" + s.fluid.backend +
                           "' backend does not move particles: it is zero in every frame");
  }
}

}  // namespace sadr::orchestrator::detail
