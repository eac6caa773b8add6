// SPDX-License-Identifier: MIT
// Scene section "boundary_fluxes" (docs/scene-format.md): a Neumann flux whose density is a rate
// law of the concentrations next to a box face or a surface of the geometry, lowered to a
// reaction that fires only in the first layer of fluid particles there, each with its share A_i
// of the face's or surface's area (docs/method.md 4d).
#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <string>

#include "sadr/common/status.hpp"
#include "sadr/fluid/backend_schema.hpp"
#include "sadr/orchestrator/boundary_share.hpp"
#include "sadr/orchestrator/reaction_equation.hpp"
#include "scene_parts.hpp"

namespace sadr::orchestrator::detail {

namespace {

constexpr std::array<std::string_view, 8> kFluxKeys{"name",    "equation", "species", "face",
                                                    "surface", "group",    "region",  "law"};
constexpr std::array<std::string_view, 6> kFaces{"x-", "x+", "y-", "y+", "z-", "z+"};

void add_flux(SceneContext& ctx, const Field& f, std::set<std::string>& names, Reaction rx) {
  if (!names.insert(rx.name).second) {
    ctx.reader.error(YamlReader::child(f, "name"), "name '" + rx.name +
                                                       "' is already used by a reaction or flux; "
                                                       "names must be unique");
  }
  ctx.scene.reactions.push_back(std::move(rx));
}

}  // namespace

void read_boundary_fluxes(SceneContext& ctx, const Field& root);

}  // namespace sadr::orchestrator::detail

namespace sadr::orchestrator {

BoundaryShare boundary_share(const ParticleState& p, const Box& box, int axis, bool upper,
                             const Region* extent, double tol) {
  const int d = box.dimension;
  std::array<double, 3> lo{}, hi{};
  double area = 1.0;  // 1D: the face is a point, A = 1
  for (int t = 0; t < d; ++t) {
    lo[t] = box.lo[t];
    hi[t] = box.hi[t];
    if (t == axis) continue;
    if (extent && extent->shape == RegionShape::kBox) {
      lo[t] = std::max(lo[t], extent->lower[t]);
      hi[t] = std::min(hi[t], extent->upper[t]);
    } else if (extent && extent->shape == RegionShape::kChannel && extent->axis == t) {
      lo[t] = std::max(lo[t], extent->axis_lower);
      hi[t] = std::min(hi[t], extent->axis_upper);
    }
    if (!(hi[t] > lo[t])) {
      throw InvalidArgument("the region's part of the face is empty along axis " +
                            std::to_string(t) + " ([" + std::to_string(lo[t]) + ", " +
                            std::to_string(hi[t]) + "])");
    }
    area *= hi[t] - lo[t];
  }
  // Candidates: fluid particles whose tangential coordinates lie on the face's patch.
  std::vector<std::uint32_t> cand;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kind(i) != ParticleKind::kFluid) continue;
    bool on = true;
    for (int t = 0; t < d && on; ++t) {
      const double x = p.positions[3 * i + t];
      if (t != axis) on = x >= lo[t] - tol && x <= hi[t] + tol;
    }
    if (on) cand.push_back(static_cast<std::uint32_t>(i));
  }
  if (cand.empty()) {
    throw InvalidArgument("no fluid particle lies on the face's part inside the region");
  }
  // The first layer: within half a particle spacing l_i = V_i^(1/d) of the outermost one.
  double edge = upper ? -HUGE_VAL : HUGE_VAL;
  for (const auto i : cand) {
    const double x = p.positions[3 * i + axis];
    edge = upper ? std::max(edge, x) : std::min(edge, x);
  }
  BoundaryShare s;
  s.area = area;
  double wsum = 0;
  std::vector<double> w;
  for (const auto i : cand) {
    const double l = std::pow(p.volume(i), 1.0 / d);
    if (std::fabs(p.positions[3 * i + axis] - edge) > 0.5 * l) continue;
    s.particles.push_back(i);
    w.push_back(std::pow(l, d - 1.0));  // the particle's own face, l^(d-1)
    wsum += w.back();
  }
  double sum = 0;
  for (std::size_t k = 0; k < w.size(); ++k) {
    s.areas.push_back(area * w[k] / wsum);
    sum += s.areas.back();
  }
  if (!(std::fabs(sum - area) <= 1e-12 * area)) {
    throw Error(StatusCode::kInternal, "boundary shares sum to " + std::to_string(sum) +
                                           " for an area of " + std::to_string(area));
  }
  return s;
}

BoundaryShare surface_share(const ParticleState& p, std::span<const int> surface_id,
                            std::span<const double> distance, int surface, double spacing,
                            std::optional<double> area, std::span<const std::uint8_t> part) {
  const int d = p.dimension;
  std::vector<std::uint32_t> cand;
  double dmin = HUGE_VAL;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kind(i) != ParticleKind::kFluid || surface_id[i] != surface) continue;
    if (!std::isfinite(distance[i]) || (!part.empty() && !part[i])) continue;
    cand.push_back(static_cast<std::uint32_t>(i));
    dmin = std::min(dmin, distance[i]);
  }
  if (cand.empty()) {
    throw InvalidArgument(std::string("no fluid particle lies next to the surface") +
                          (part.empty() ? "" : "'s part"));
  }
  const double limit = dmin + (1.0 - 1e-9) * spacing;
  BoundaryShare s;
  std::vector<double> w;
  for (const auto i : cand) {
    if (!(distance[i] < limit)) continue;
    s.particles.push_back(i);
    w.push_back(std::pow(p.volume(i), (d - 1.0) / d));  // l_i^(d-1)
    s.layer_area += w.back();
  }
  s.area = area.value_or(s.layer_area);
  double sum = 0;
  for (const double wk : w) {
    s.areas.push_back(s.area * wk / s.layer_area);
    sum += s.areas.back();
  }
  if (!(std::fabs(sum - s.area) <= 1e-12 * s.area)) {
    throw Error(StatusCode::kInternal, "surface shares sum to " + std::to_string(sum) +
                                           " for an area of " + std::to_string(s.area));
  }
  return s;
}

}  // namespace sadr::orchestrator

namespace sadr::orchestrator::detail {

void read_boundary_fluxes(SceneContext& ctx, const Field& root) {
  YamlReader& r = ctx.reader;
  const Field list = YamlReader::child(root, "boundary_fluxes");
  if (!YamlReader::present(list) || !r.expect_sequence(list)) return;
  std::set<std::string> names;
  for (const auto& rx : ctx.scene.reactions) names.insert(rx.name);
  for (std::size_t k = 0; k < list.node.size(); ++k) {
    const Field f = YamlReader::element(list, k);
    if (!r.expect_map(f, kFluxKeys)) continue;
    Reaction rx;
    rx.name = r.string(f, "name", false).value_or("flux" + std::to_string(k));
    const Field eqf = YamlReader::child(f, "equation");
    const Field spf = YamlReader::child(f, "species");
    if (YamlReader::present(eqf) == YamlReader::present(spf)) {
      r.error(f,
              "give either 'species' (an influx, \"0 -> X\") or 'equation' (e.g. \"S -> P\": "
              "S leaves and P enters the fluid at the rate of the law)");
      continue;
    }
    if (YamlReader::present(spf)) {
      if (auto name = r.string(f, "species", true)) rx.products.push_back({*name, 1});
    } else if (auto text = r.string(f, "equation", true)) {
      try {
        ReactionEquation eq = parse_reaction_equation(*text);
        if (eq.reversible) throw InvalidArgument("a boundary flux is irreversible ('->')");
        rx.reactants = std::move(eq.reactants);
        rx.products = std::move(eq.products);
      } catch (const InvalidArgument& e) {
        r.error(eqf, e.what());
        continue;
      }
    }
    const Field where = YamlReader::present(eqf) ? eqf : spf;
    const auto stochastic = check_reaction_species(ctx, where, rx);
    const Field ff = YamlReader::child(f, "face");
    const Field sf = YamlReader::child(f, "surface");
    if (YamlReader::present(ff) && YamlReader::present(sf)) {
      r.error(sf,
              "give either 'face' (a box face, e.g. y-) or 'surface' (a fluid or solid body of "
              "'geometry'), not both");
      continue;
    }
    const bool on_surface = YamlReader::present(sf);
    if (!on_surface && YamlReader::present(YamlReader::child(f, "group"))) {
      r.error(YamlReader::child(f, "group"),
              "'group' names a part of a body's surface and needs 'surface' (the body); "
              "allowed: 'group' with 'surface' only");
      continue;
    }
    const auto face =
        on_surface ? std::optional<std::string>{} : r.choice(f, "face", kFaces, false, "face");
    const auto surface = on_surface ? r.string(f, "surface", true) : std::nullopt;
    if (!on_surface && !YamlReader::present(ff)) {
      r.error(f,
              "missing 'face' or 'surface'; required: one of them: 'face' (x-, x+, y-, y+, z-, "
              "z+: a box face) or 'surface' (the name of a fluid or solid body of 'geometry')");
    }
    if (!YamlReader::present(YamlReader::child(f, "law"))) {
      r.error(f,
              "missing 'law': the flux density j [molecules/(length^(d-1) time)], e.g. "
              "{type: expression, expression: \"q\"}");
      continue;
    }
    if (!stochastic || (!face && !surface)) continue;
    rx.stochastic = *stochastic;
    read_law(ctx, f, rx);
    if (!*stochastic) {
      const auto* b = sadr::fluid::schema::find(ctx.scene.fluid.backend);
      if (b && !b->capabilities.boundary_fluxes) {
        r.error(f, "the '" + ctx.scene.fluid.backend +
                       "' backend has no boundary fluxes of deterministic species (capability "
                       "'boundary fluxes', `sadr backends`); allowed: a backend with them, or "
                       "stochastic species");
        continue;
      }
    }
    if (surface) {
      if (read_surface_share(ctx, f, root, *surface, rx)) add_flux(ctx, f, names, std::move(rx));
      continue;
    }
    const int axis = (*face)[0] - 'x';
    if (!ctx.geometry_ok || !ctx.particles_ok) continue;
    if (axis >= ctx.scene.box.dimension) {
      r.error(ff, "face '" + *face + "' is not a face of a " +
                      std::to_string(ctx.scene.box.dimension) + "D box");
      continue;
    }
    if (ctx.scene.box.periodic[axis]) {
      r.error(ff, "face '" + *face + "' is on a periodic axis; allowed: a walled axis");
      continue;
    }
    const Region* extent = nullptr;
    if (auto rn = r.string(f, "region", false)) {
      extent = lookup_region(ctx, YamlReader::child(f, "region"), *rn);
      if (!extent) continue;
      if (extent->shape != RegionShape::kBox && extent->shape != RegionShape::kChannel &&
          extent->shape != RegionShape::kAll) {
        r.error(YamlReader::child(f, "region"),
                "region '" + *rn + "' has shape " + std::string(to_string(extent->shape)) +
                    "; allowed: box or channel (its extent along the face)");
        continue;
      }
    }
    try {
      BoundaryShare s = boundary_share(ctx.scene.particles, ctx.scene.box, axis, (*face)[1] == '+',
                                       extent, ctx.tolerance());
      rx.boundary_particles = std::move(s.particles);
      rx.boundary_areas = std::move(s.areas);
    } catch (const InvalidArgument& e) {
      r.error(
          YamlReader::present(YamlReader::child(f, "region")) ? YamlReader::child(f, "region") : ff,
          "boundary flux '" + rx.name + "' on face " + *face + ": " + e.what());
      continue;
    }
    add_flux(ctx, f, names, std::move(rx));
  }
}

}  // namespace sadr::orchestrator::detail
