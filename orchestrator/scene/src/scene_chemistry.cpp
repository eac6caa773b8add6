// SPDX-License-Identifier: MIT
// Scene sections "species" and "reactions".
#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <span>

#include "sadr/common/status.hpp"
#include "sadr/fluid/backend_schema.hpp"
#include "sadr/orchestrator/reaction_equation.hpp"
#include "scene_parts.hpp"

namespace sadr::orchestrator::detail {

namespace {

constexpr std::array<std::string_view, 5> kSpeciesKeys{"name", "stochastic", "diffusivity",
                                                       "initial", "boundaries"};
constexpr std::array<std::string_view, 5> kInitialKeys{"region", "count", "concentration",
                                                       "count_column", "concentration_column"};
constexpr std::array<std::string_view, 6> kBoundaryKeys{"region",    "surface", "group",
                                                        "condition", "value",   "count"};
constexpr std::array<std::string_view, 5> kConditions{"dirichlet", "neumann", "none", "free",
                                                      "inflow"};
constexpr std::array<std::string_view, 9> kReactionKeys{
    "name", "equation", "reactants", "products", "rate", "reverse_rate", "regions", "kinds", "law"};
constexpr std::array<std::string_view, 4> kChemistryKinds{"fluid", "wall", "inlet", "outlet"};

/// The largest stochastic copy number a scene accepts: kMaxExactCount (2^53,
/// scene_parts.hpp). Above it, the conversion to the SSA's 64-bit counts
/// overflowed (1e19 arrived as -2^63).
constexpr double kMaxCopyNumber = kMaxExactCount;
const std::string kCopyNumberRange = "a whole number 0 <= n <= 2^53 = 9007199254740992";

/// Copy number for a concentration in particle i: nearest whole number of C V_i.
double to_count(const ParticleState& p, std::size_t i, double concentration) {
  return std::round(concentration * p.volume(i));
}

/// Reports a copy number beyond the exact integer range of a double (and of
/// the SSA's 64-bit counters), or a non-finite concentration; true if it is fine.
bool check_amount(YamlReader& r, const Field& where, const Species& sp, std::size_t particle,
                  double value) {
  if (sp.stochastic && !(value <= kMaxExactCount)) {
    r.error(where, format_number(value) + " molecules in particle " + std::to_string(particle) +
                       " of the stochastic species '" + sp.name +
                       "' is out of range; allowed: at most 2^53 = 9007199254740992 per "
                       "particle (exact integers)");
    return false;
  }
  if (!sp.stochastic && !std::isfinite(value)) {
    r.error(where, "the concentration of '" + sp.name + "' in particle " +
                       std::to_string(particle) + " overflows (" + format_number(value) +
                       "); allowed: a finite number");
    return false;
  }
  return true;
}

/// `count_column` / `concentration_column` of an initial entry: per-particle
/// values from a column of the particle file. False if the entry has neither.
bool read_initial_column(SceneContext& ctx, const Field& f, Species& sp, const Region* rg) {
  YamlReader& r = ctx.reader;
  const bool is_count = YamlReader::present(YamlReader::child(f, "count_column"));
  const std::string_view key = is_count ? "count_column" : "concentration_column";
  const Field cf = YamlReader::child(f, key);
  if (!YamlReader::present(cf)) return false;
  const auto name = r.string(f, key, true);
  if (!name) return true;
  if (!ctx.particle_file_field) {
    r.error(cf, "needs a particle file (particles.file); a lattice has no columns");
    return true;
  }
  auto it = std::find_if(ctx.extra_columns.begin(), ctx.extra_columns.end(),
                         [&](const auto& c) { return c.name == *name; });
  if (it == ctx.extra_columns.end()) {
    std::vector<std::string_view> known;
    for (const auto& c : ctx.extra_columns) known.push_back(c.name);
    std::string msg = "the particle file '" + ctx.particle_file + "' has no column '" + *name + "'";
    if (auto near = nearest_name(*name, known)) msg += "; did you mean '" + *near + "'?";
    msg += " (value columns: " + (known.empty() ? std::string("none") : join_names(known)) + ")";
    r.error(cf, msg);
    return true;
  }
  it->used = true;
  if (!rg || !ctx.particles_ok) return true;
  const ParticleState& p = ctx.scene.particles;
  std::size_t reported = 0;
  for (const std::uint32_t i : rg->particles) {
    const double v = it->values[i];
    std::string bad;
    if (!(v >= 0.0)) {
      bad = "is out of range; allowed: >= 0";
    } else if (sp.stochastic && ((is_count && v != std::floor(v)) ||
                                 (is_count ? v : to_count(p, i, v)) > kMaxCopyNumber)) {
      bad = "is not allowed for the stochastic species '" + sp.name +
            "'; allowed: " + (is_count ? kCopyNumberRange : "a copy number C V <= 2^53");
    }
    if (!bad.empty()) {
      if (++reported <= 5) {
        r.error(cf, ctx.particle_file + ":" + std::to_string(ctx.particle_lines[i]) + ": column '" +
                        *name + "': " + format_number(v) + " " + bad);
      }
      continue;
    }
    if (is_count) {
      sp.initial[i] = sp.stochastic ? v : v / p.volume(i);
    } else {
      sp.initial[i] = sp.stochastic ? to_count(p, i, v) : v;
    }
    if (!check_amount(r, cf, sp, i, sp.initial[i])) break;
  }
  if (reported > 5) {
    r.error(cf, ctx.particle_file + ": " + std::to_string(reported - 5) +
                    " more bad values in column '" + *name + "'");
  }
  return true;
}

void read_initial(SceneContext& ctx, const Field& sp_field, Species& sp) {
  YamlReader& r = ctx.reader;
  const ParticleState& p = ctx.scene.particles;
  if (ctx.particles_ok) sp.initial.assign(p.size(), 0.0);
  const Field list = YamlReader::child(sp_field, "initial");
  if (!r.expect_sequence(list)) return;
  for (std::size_t k = 0; k < list.node.size(); ++k) {
    const Field f = YamlReader::element(list, k);
    if (!r.expect_map(f, kInitialKeys)) continue;
    const std::string name = r.string(f, "region", false).value_or(std::string(kAllRegion));
    const Region* rg = lookup_region(ctx, YamlReader::child(f, "region"), name);
    int given = 0;
    for (const auto key : std::span(kInitialKeys).subspan(1)) {
      given += YamlReader::present(YamlReader::child(f, key)) ? 1 : 0;
    }
    if (given != 1) {
      r.error(f,
              "give exactly one of 'count' (molecules per particle), 'concentration' "
              "(molecules/length^d), 'count_column' or 'concentration_column' (a column of the "
              "particle file)");
      continue;
    }
    if (rg && ctx.particles_ok && rg->particles.empty()) {
      r.error(YamlReader::child(f, "region"),
              "region '" + name + "' holds no particle; an initial value needs at least one");
      continue;
    }
    if (read_initial_column(ctx, f, sp, rg)) continue;
    const auto count = r.number(f, "count", Bound::kNonNegative, "molecules per particle", false);
    const auto conc =
        r.number(f, "concentration", Bound::kNonNegative, "molecules/length^d", false);
    if (count && sp.stochastic && (*count != std::floor(*count) || *count > kMaxCopyNumber)) {
      r.error(YamlReader::child(f, "count"), format_number(*count) +
                                                 " is not allowed for the stochastic species '" +
                                                 sp.name + "'; allowed: " + kCopyNumberRange);
      continue;
    }
    if (!rg || !ctx.particles_ok || !(count || conc)) continue;
    if (conc && sp.stochastic) {
      const auto too_many =
          std::find_if(rg->particles.begin(), rg->particles.end(),
                       [&](std::uint32_t i) { return to_count(p, i, *conc) > kMaxCopyNumber; });
      if (too_many != rg->particles.end()) {
        r.error(YamlReader::child(f, "concentration"),
                format_number(*conc) + " gives " + format_number(to_count(p, *too_many, *conc)) +
                    " molecules in particle " + std::to_string(*too_many) +
                    " of the stochastic species '" + sp.name +
                    "'; allowed: a copy number C V <= 2^53 = 9007199254740992");
        continue;
      }
    }
    const Field value_field = YamlReader::child(f, count ? "count" : "concentration");
    for (const std::uint32_t i : rg->particles) {
      if (count) {
        sp.initial[i] = sp.stochastic ? *count : *count / p.volume(i);
      } else {
        sp.initial[i] = sp.stochastic ? to_count(p, i, *conc) : *conc;
      }
      if (!check_amount(r, value_field, sp, i, sp.initial[i])) break;
    }
    if (conc) warn_rounds_to_zero(ctx, value_field, sp, *rg, *conc);
  }
}

/// Whether the scene's fluid backend integrates deterministic species terms on wall particles
/// (schema capability `wall_species_terms`); an unknown backend is reported elsewhere.
bool backend_has_wall_species_terms(const SceneContext& ctx) {
  const auto* b = sadr::fluid::schema::find(ctx.scene.fluid.backend);
  return b == nullptr || b->capabilities.wall_species_terms;
}

/// Refuses a deterministic species term on wall particles that the backend would drop.
void refuse_wall_term(SceneContext& ctx, const Field& at, const std::string& what) {
  ctx.reader.error(at, what + " on wall particles: the '" + ctx.scene.fluid.backend +
                           "' backend does not integrate deterministic species on wall "
                           "particles (it would be silently dropped); allowed: a backend with "
                           "wall species terms (`sadr backends`), a stochastic species, or "
                           "fluid particles only");
}

/// The region of the wall particles `walls` that a species boundary names with `surface` (and
/// `group`): `base` ("BODY/GROUP", or "BODY/surface"; never a scene name, which is an
/// identifier), reused when a region of that name holds the same particles, else `base#2`, ...
const Region* surface_region(SceneContext& ctx, const std::string& base,
                             std::vector<std::uint32_t> walls) {
  Scene& s = ctx.scene;
  for (int n = 1;; ++n) {
    const std::string name = n == 1 ? base : base + "#" + std::to_string(n);
    const Region* old = s.find_region(name);
    if (old && old->ids == walls) return old;
    if (old) continue;
    Region rg;
    rg.name = name;
    rg.shape = RegionShape::kIds;
    rg.ids = std::move(walls);
    resolve_membership(rg, s.particles, ctx.tolerance());
    s.regions.push_back(std::move(rg));
    return &s.regions.back();
  }
}

/// The region of a boundary entry: `region: NAME`, or the wall particles behind `surface: BODY`
/// (with `group: NAME`) as a region of their own (surface_region). A wall particle that an
/// earlier entry's group of the same body already holds (one as near to two groups, behind a
/// corner) stays with that entry: `owner` (per particle, the entry holding it) and `group_of`
/// (per entry, "BODY/GROUP" for a group entry) say which. Null after an error.
const Region* boundary_region(SceneContext& ctx, const Field& f, const Field& root,
                              const std::vector<int>& owner,
                              const std::vector<std::string>& group_of, std::string& group) {
  YamlReader& r = ctx.reader;
  const Field rf = YamlReader::child(f, "region");
  const Field sf = YamlReader::child(f, "surface");
  const Field gf = YamlReader::child(f, "group");
  if (YamlReader::present(rf) && YamlReader::present(sf)) {
    r.error(sf,
            "give either 'region' (a region's non-fluid particles) or 'surface' (the walls "
            "behind a fluid or solid body's surface, or with 'group' behind a part of it), "
            "not both");
    return nullptr;
  }
  if (YamlReader::present(gf) && !YamlReader::present(sf)) {
    r.error(gf,
            "'group' names a part of a body's surface and needs 'surface' (the body); "
            "allowed: 'group' with 'surface' only");
    return nullptr;
  }
  if (!YamlReader::present(sf)) {
    const auto name = r.string(f, "region", true);
    return name ? lookup_region(ctx, rf, *name) : nullptr;
  }
  auto walls = surface_walls(ctx, f, root);
  if (!walls) return nullptr;
  const std::string body = r.string(f, "surface", true).value_or("");
  const auto gname = YamlReader::present(gf) ? r.string(f, "group", true) : std::nullopt;
  group = gname ? body + "/" + *gname : std::string();
  if (gname) {
    std::erase_if(*walls, [&](std::uint32_t i) {
      const int o = owner.empty() ? -1 : owner[i];
      if (o < 0) return false;
      const std::string& held = group_of[static_cast<std::size_t>(o)];
      return !held.empty() && held.substr(0, held.find('/')) == body;
    });
    if (walls->empty()) {
      r.error(gf, "every wall particle behind group '" + *gname + "' of '" + body +
                      "' is held by an earlier entry's group of the same body; allowed: a group "
                      "with walls of its own behind it");
      return nullptr;
    }
  }
  return surface_region(ctx, gname ? group : body + "/surface", std::move(*walls));
}

void read_boundaries(SceneContext& ctx, const Field& sp_field, const Field& root, Species& sp) {
  YamlReader& r = ctx.reader;
  const ParticleState& p = ctx.scene.particles;
  const Field list = YamlReader::child(sp_field, "boundaries");
  if (!r.expect_sequence(list)) return;
  std::vector<int> owner(ctx.particles_ok ? p.size() : 0, -1);
  std::vector<std::string> group_of(list.node.size());
  for (std::size_t k = 0; k < list.node.size(); ++k) {
    const Field f = YamlReader::element(list, k);
    if (!r.expect_map(f, kBoundaryKeys)) continue;
    SpeciesBoundary b;
    const bool on_surface = YamlReader::present(YamlReader::child(f, "surface"));
    const Field rf = YamlReader::child(f, on_surface ? "surface" : "region");
    const Region* rg = boundary_region(ctx, f, root, owner, group_of, group_of[k]);
    const auto cond = r.choice(f, "condition", kConditions, true, "boundary condition");
    if (!cond) continue;
    b.condition = *cond == "dirichlet" ? BoundaryCondition::kDirichlet
                  : *cond == "neumann" ? BoundaryCondition::kNeumann
                  : *cond == "free"    ? BoundaryCondition::kFree
                  : *cond == "inflow"  ? BoundaryCondition::kInflow
                                       : BoundaryCondition::kNone;
    if (!sp.stochastic && !backend_has_wall_species_terms(ctx) &&
        b.condition == BoundaryCondition::kFree) {
      refuse_wall_term(
          ctx, YamlReader::child(f, "condition"),
          "condition '" + std::string(*cond) + "' of the deterministic species '" + sp.name + "'");
    }
    const bool inflow = b.condition == BoundaryCondition::kInflow;
    const bool held = b.condition == BoundaryCondition::kDirichlet || inflow;
    if (inflow && on_surface) {
      r.error(rf,
              "condition 'inflow' needs a region of shape box or channel (it holds whatever "
              "particles are inside the shape at each step), and 'surface' names fixed wall "
              "particles; allowed: 'region' with a box or channel region");
      continue;
    }
    if (inflow && rg && rg->shape != RegionShape::kBox && rg->shape != RegionShape::kChannel) {
      r.error(rf, "condition 'inflow' needs a region of shape box or channel ('" + rg->name +
                      "' is a " + std::string(to_string(rg->shape)) + ")");
    }
    const Field count_field = YamlReader::child(f, "count");
    std::optional<double> count;
    if (YamlReader::present(count_field)) {
      if (!held) {
        r.error(count_field, "'count' applies to conditions 'dirichlet' and 'inflow' only");
      } else if (YamlReader::present(YamlReader::child(f, "value"))) {
        r.error(count_field,
                "give either 'value' (concentration) or 'count' (molecules per "
                "particle), not both");
      } else {
        count = r.number(f, "count", Bound::kNonNegative, "molecules per particle", true);
        if (!count) continue;
      }
    }
    if (count) {
      // Converted to the concentration count / V; needs equal volumes in the region.
      if (rg && ctx.particles_ok) {
        double volume = 0.0;
        bool uniform = true;
        for (const std::uint32_t i : rg->particles) {
          if (p.kind(i) == ParticleKind::kFluid && !inflow) continue;
          if (volume == 0.0) volume = p.volume(i);
          uniform = uniform && std::abs(p.volume(i) - volume) <= 1e-12 * volume;
        }
        if (!uniform) {
          r.error(count_field, "'count' needs equal particle volumes (m/rho) in region '" +
                                   rg->name + "'; give 'value' (a concentration) instead");
        } else if (volume > 0.0) {
          b.value = *count / volume;
        }
      }
    } else if (held) {
      b.value = r.number(f, "value", Bound::kNonNegative, "molecules/length^d", true).value_or(0);
    } else if (b.condition == BoundaryCondition::kNeumann) {
      b.value =
          r.number(f, "value", Bound::kAny, "molecules/(length^(d-1) time)", true).value_or(0);
    } else if (YamlReader::present(YamlReader::child(f, "value"))) {
      r.error(YamlReader::child(f, "value"),
              "a value has no meaning for condition '" + *cond + "'; remove it");
    }
    if (!rg) continue;
    b.region = rg->name == kAllRegion ? std::string() : rg->name;
    if (inflow) {  // geometric, re-evaluated on the moving particles by the service
      if (ctx.particles_ok && sp.stochastic) {
        std::size_t largest = 0;  // the particle with the largest volume gets the most
        for (std::size_t i = 1; i < p.size(); ++i) {
          if (p.volume(i) > p.volume(largest)) largest = i;
        }
        check_amount(r, YamlReader::child(f, count ? "count" : "value"), sp, largest,
                     to_count(p, largest, b.value));
      }
      sp.boundaries.push_back(b);
      continue;
    }
    if (ctx.particles_ok) {
      std::size_t fluid = 0;
      for (const std::uint32_t i : rg->particles) {
        if (p.kind(i) == ParticleKind::kFluid) {
          ++fluid;
        } else if (owner[i] >= 0) {
          const std::string what = on_surface ? "the walls behind '" + rg->name + "' overlap"
                                              : "region '" + rg->name + "' overlaps";
          r.error(rf, what + " the region of " + list.path + "[" + std::to_string(owner[i]) +
                          "] (particle " + std::to_string(i) +
                          "); a particle can have one condition per species");
          break;
        } else {
          owner[i] = static_cast<int>(k);
        }
      }
      if (rg->particles.size() == fluid) {
        r.error(rf, "region '" + rg->name +
                        "' holds no wall, inlet or outlet particles; "
                        "boundary conditions apply to non-fluid particles");
      }
      if (b.condition == BoundaryCondition::kDirichlet && !sp.initial.empty()) {
        const Field value_field = YamlReader::child(f, count ? "count" : "value");
        for (const std::uint32_t i : rg->particles) {
          if (p.kind(i) == ParticleKind::kFluid) continue;
          sp.initial[i] = sp.stochastic ? to_count(p, i, b.value) : b.value;
          if (!check_amount(r, value_field, sp, i, sp.initial[i])) break;
        }
      }
    }
    sp.boundaries.push_back(b);
  }
}

std::vector<ParticleKind> read_kinds(SceneContext& ctx, const Field& f) {
  std::vector<ParticleKind> kinds;
  auto names = ctx.reader.string_list(f, "kinds", false);
  if (!names) kinds = {ParticleKind::kFluid};
  for (const auto& k : names ? *names : std::vector<std::string>{}) {
    if (auto kind = parse_kind(k)) {
      kinds.push_back(*kind);
    } else {
      ctx.reader.error(
          YamlReader::child(f, "kinds"),
          "unknown particle kind '" + k + "' (allowed: " + join_names(kChemistryKinds) + ")");
    }
  }
  return kinds;
}

std::vector<StoichiometryEntry> read_stoichiometry(SceneContext& ctx, const Field& parent,
                                                   std::string_view key) {
  std::vector<StoichiometryEntry> out;
  const Field f = YamlReader::child(parent, key);
  if (!YamlReader::present(f)) return out;
  if (!f.node.IsMap()) {
    ctx.reader.error(f, "expected a map species: coefficient (e.g. {A: 1, B: 1})");
    return out;
  }
  for (const auto& kv : f.node) {
    const std::string name = kv.first.Scalar();
    if (auto n = ctx.reader.integer(f, name, 1, 1000, true)) {
      out.push_back({name, static_cast<std::uint32_t>(*n)});
    }
  }
  return out;
}

}  // namespace

/// Checks the species of a reaction; returns whether they are stochastic
/// (nullopt if unknown or mixed; reported).
std::optional<bool> check_reaction_species(SceneContext& ctx, const Field& where,
                                           const Reaction& rx) {
  std::vector<std::string_view> known;
  for (const auto& sp : ctx.scene.species) known.push_back(sp.name);
  std::optional<bool> stochastic;
  bool ok = true;
  std::string first_name;
  for (const auto* side : {&rx.reactants, &rx.products}) {
    for (const auto& e : *side) {
      const Species* sp = ctx.scene.find_species(e.species);
      if (!sp) {
        std::string msg = "unknown species '" + e.species + "'";
        if (auto near = nearest_name(e.species, known)) msg += "; did you mean '" + *near + "'?";
        msg += " (declared: " + (known.empty() ? std::string("none") : join_names(known)) + ")";
        ctx.reader.error(where, msg);
        ok = false;
        continue;
      }
      if (!stochastic) {
        stochastic = sp->stochastic;
        first_name = sp->name;
      } else if (*stochastic != sp->stochastic) {
        ctx.reader.error(
            where, "mixes " + std::string(*stochastic ? "stochastic" : "deterministic") +
                       " species '" + first_name + "' with " +
                       (sp->stochastic ? "stochastic" : "deterministic") + " species '" + sp->name +
                       "'; a reaction changes the species of one path only (it fires in the "
                       "SSA or in the fluid): split it into one reaction per path, or leave the "
                       "species it does not change out of the equation and read it in a 'law' "
                       "(a hybrid reaction, docs/method.md section 4c)");
        ok = false;
      }
    }
  }
  if (!ok) return std::nullopt;
  return stochastic.value_or(true);
}

void read_species(SceneContext& ctx, const Field& root) {
  YamlReader& r = ctx.reader;
  const Field list = YamlReader::child(root, "species");
  if (r.expect_sequence(list)) {
    std::set<std::string> names;
    for (std::size_t k = 0; k < list.node.size(); ++k) {
      const Field f = YamlReader::element(list, k);
      const bool assigned = f.node.IsMap() && YamlReader::present(YamlReader::child(f, "assigned"));
      if (!assigned && !r.expect_map(f, kSpeciesKeys)) continue;
      Species sp;
      sp.name = r.string(f, "name", true).value_or("");
      const Field nf = YamlReader::child(f, "name");
      if (!sp.name.empty() && !valid_identifier(sp.name)) {
        r.error(nf,
                "'" + sp.name + "' is not a valid species name; allowed: [A-Za-z_][A-Za-z0-9_]*");
      } else if (!sp.name.empty() && !names.insert(sp.name).second) {
        r.error(nf, "species name '" + sp.name + "' is already used; species names must be unique");
      }
      if (assigned) {
        read_assigned(ctx, f);
        continue;
      }
      sp.stochastic = r.boolean(f, "stochastic", false).value_or(true);
      sp.diffusivity =
          r.number(f, "diffusivity", Bound::kNonNegative, "length^2/time", true).value_or(0.0);
      read_initial(ctx, f, sp);
      read_boundaries(ctx, f, root, sp);
      model::Problems problems;  // the model's range checks, reported at their keys
      model::check(sp, problems);
      const std::pair<std::string_view, std::string_view> units[] = {
          {"diffusivity", "length^2/time"}};
      r.report(f, problems, units);
      warn_inert_wall_molecules(ctx, f, sp);
      warn_absorbing_walls(ctx, f, sp);
      ctx.scene.species.push_back(std::move(sp));
    }
  }
  check_assigned(ctx, root);
  for (const auto& c : ctx.extra_columns) {
    if (c.used) continue;
    r.error(*ctx.particle_file_field,
            ctx.particle_file + ":1: unknown column '" + c.name +
                "' (allowed: x, y, z, mass, density, kind, vx, vy, vz, or a column read by a "
                "species' initial count_column or concentration_column)");
  }
  if (ctx.boussinesq && ctx.scene.fluid.boussinesq) {
    const std::string& name = ctx.scene.fluid.boussinesq->species;
    if (!name.empty() && !ctx.scene.find_species(name)) {
      std::vector<std::string_view> known;
      for (const auto& sp : ctx.scene.species) known.push_back(sp.name);
      std::string msg = "unknown species '" + name + "'";
      if (auto near = nearest_name(name, known)) msg += "; did you mean '" + *near + "'?";
      r.error(YamlReader::child(*ctx.boussinesq, "species"), msg);
    }
  }
}

void read_reactions(SceneContext& ctx, const Field& root) {
  YamlReader& r = ctx.reader;
  const Field list = YamlReader::child(root, "reactions");
  if (!r.expect_sequence(list)) return;
  std::set<std::string> names;
  for (std::size_t k = 0; k < list.node.size(); ++k) {
    const Field f = YamlReader::element(list, k);
    if (f.node.IsScalar()) {
      r.error(f, "'" + f.node.Scalar() + "' needs a rate; write {equation: \"" + f.node.Scalar() +
                     "\", rate: k}");
      continue;
    }
    if (!r.expect_map(f, kReactionKeys)) continue;
    Reaction rx;
    bool reversible = false;
    const Field eqf = YamlReader::child(f, "equation");
    const bool structured = YamlReader::present(YamlReader::child(f, "reactants")) ||
                            YamlReader::present(YamlReader::child(f, "products"));
    if (YamlReader::present(eqf) == structured) {
      r.error(f, "give either 'equation' (e.g. \"A + B -> C\") or 'reactants'/'products' maps");
      continue;
    }
    if (structured) {
      rx.reactants = read_stoichiometry(ctx, f, "reactants");
      rx.products = read_stoichiometry(ctx, f, "products");
    } else if (auto text = r.string(f, "equation", true)) {
      try {
        ReactionEquation eq = parse_reaction_equation(*text);
        rx.reactants = std::move(eq.reactants);
        rx.products = std::move(eq.products);
        reversible = eq.reversible;
      } catch (const InvalidArgument& e) {
        r.error(eqf, e.what());
        continue;
      }
    }
    rx.name = r.string(f, "name", false).value_or("reaction" + std::to_string(k));
    const std::string unit = rx.order() == 0   ? "molecules/(length^d time)"
                             : rx.order() == 1 ? "1/time"
                                               : "length^d/(molecules time)";
    const bool has_law = YamlReader::present(YamlReader::child(f, "law"));
    if (has_law && YamlReader::present(YamlReader::child(f, "rate"))) {
      r.error(YamlReader::child(f, "rate"),
              "give either 'rate' (mass action) or 'law' (another rate law), not both");
    } else if (has_law && reversible) {
      r.error(eqf,
              "a reaction with a 'law' is irreversible ('->'); write the reverse "
              "reaction as its own entry");
    } else if (!has_law) {
      rx.rate = r.number(f, "rate", Bound::kNonNegative, unit, true).value_or(0.0);
    }
    const Field rev = YamlReader::child(f, "reverse_rate");
    std::optional<double> reverse;
    if (reversible) {
      reverse = r.number(f, "reverse_rate", Bound::kNonNegative, "per the reverse order", true);
    } else if (YamlReader::present(rev)) {
      r.error(rev, "only a reversible reaction ('<->') has a reverse_rate");
    }
    rx.kinds = read_kinds(ctx, f);
    if (auto regions = r.string_list(f, "regions", false)) {
      for (const auto& name : *regions) {
        if (const Region* rg = lookup_region(ctx, YamlReader::child(f, "regions"), name)) {
          if (rg->name == kAllRegion) {
            rx.regions.clear();
            break;
          }
          rx.regions.push_back(rg->name);
        }
      }
    }
    const auto stochastic = check_reaction_species(ctx, eqf.node.IsDefined() ? eqf : f, rx);
    if (stochastic) rx.stochastic = *stochastic;
    if (stochastic && !*stochastic && !backend_has_wall_species_terms(ctx) &&
        std::any_of(rx.kinds.begin(), rx.kinds.end(),
                    [](ParticleKind kind) { return kind != ParticleKind::kFluid; })) {
      refuse_wall_term(ctx, YamlReader::child(f, "kinds"),
                       "the deterministic reaction '" + rx.name + "' with kinds beyond fluid");
    }
    if (stochastic && has_law) read_law(ctx, f, rx);
    model::Problems problems;  // the model's range checks, reported at their keys
    model::check(rx, problems);
    const std::pair<std::string_view, std::string_view> units[] = {{"rate", unit}};
    const std::pair<std::string_view, Field> equation[] = {{"reactants", eqf}, {"products", eqf}};
    r.report(f, problems, units,
             YamlReader::present(eqf) ? std::span(equation) : std::span(equation).first(0));
    warn_reaction_selects_nothing(ctx, f, rx);
    if (!has_law && rx.rate == 0.0 && YamlReader::present(YamlReader::child(f, "rate"))) {
      r.warning(YamlReader::child(f, "rate"),
                "rate 0: reaction '" + rx.name + "' never fires (remove it, or give its rate)");
    }
    Reaction back = rx;
    back.name = rx.name + "_reverse";
    std::swap(back.reactants, back.products);
    back.rate = reverse.value_or(0.0);
    if (reversible && back.order() > 2) {
      r.error(eqf, "the reverse reaction has order " + std::to_string(back.order()) +
                       "; allowed: order 0, 1 or 2");
    }
    for (const Reaction* one : {&rx, &back}) {
      if (one == &back && !reversible) break;
      if (!names.insert(one->name).second) {
        r.error(YamlReader::child(f, "name"),
                "reaction name '" + one->name + "' is already used; names must be unique");
      }
      ctx.scene.reactions.push_back(*one);
    }
  }
}

}  // namespace sadr::orchestrator::detail
