// SPDX-License-Identifier: MIT
// Scene section "boundary_fluxes", `surface: <body>` (docs/scene-format.md "Surfaces"): the
// first fluid layer next to a fluid or solid body of the geometry section and the shares of its
// area; with `group`, only the part of a mesh body's surface that one physical group of its file
// covers; with `region`, only the part whose first-layer particles lie in that region.
#include <algorithm>
#include <string>

#include "sadr/common/status.hpp"
#include "sadr/orchestrator/boundary_share.hpp"
#include "scene_geometry_parts.hpp"

namespace sadr::orchestrator::detail {

bool read_surface_share(SceneContext& ctx, const Field& f, const Field& root,
                        const std::string& name, Reaction& rx) {
  YamlReader& r = ctx.reader;
  const Field sf = YamlReader::child(f, "surface");
  const Field gf = YamlReader::child(f, "group");
  const Field rf = YamlReader::child(f, "region");
  if (!YamlReader::present(YamlReader::child(root, "geometry"))) {
    r.error(sf,
            "'surface' names a fluid or solid body of the 'geometry' section, and the scene "
            "has none; allowed: 'face' (a box face)");
    return false;
  }
  const auto group = YamlReader::present(gf) ? r.string(f, "group", true) : std::nullopt;
  if (YamlReader::present(gf) && !group) return false;
  if (!ctx.geometry_ok || !ctx.particles_ok || !ctx.scene.geometry) return false;
  const GeometryReport& geo = *ctx.scene.geometry;
  const GeometryBody* body = surface_body(ctx, sf, name);
  if (!body) return false;
  if (body->moving) {
    r.error(sf, "'" + name +
                    "' moves (motion: {moves: true}), and a surface flux enters the fluid "
                    "particles next to the surface at t = 0; allowed: a body at rest, or the "
                    "body's wall particles with a 'free' boundary and a reaction there");
    return false;
  }
  const Region* region = nullptr;
  if (auto rn = r.string(f, "region", false)) {
    region = lookup_region(ctx, rf, *rn);
    if (!region) return false;
  } else if (YamlReader::present(rf)) {
    return false;
  }
  // The shape's own area when it gives one and nothing of it is cut off by the box.
  std::optional<double> area;
  if (body->exact_area && body->inside_box) area = body->exact_area;
  std::vector<std::uint8_t> part;
  std::string what = "'" + name + "'";
  std::string why = body->exact_area ? "cut by the box" : "not known in closed form";
  if (group) {
    auto sg = read_surface_group(ctx, gf, *body, *group, ParticleKind::kFluid);
    if (!sg) return false;
    part = std::move(sg->part);
    area = sg->inside_box ? sg->area : std::nullopt;
    what = "group '" + *group + "' of '" + name + "'";
    why = sg->inside_box ? "not known in closed form (a non-uniform scale)" : "cut by the box";
  }
  const Field at = group ? gf : sf;
  try {
    BoundaryShare s = surface_share(ctx.scene.particles, geo.surface_id, geo.surface_distance,
                                    body->surface_id, geo.spacing, area, part);
    if (area && !(s.layer_area > 0.5 * *area && s.layer_area < 2.0 * *area)) {
      r.warning(at, "the first fluid layer next to " + what + " covers about " +
                        format_number(s.layer_area) + " of its area " + format_number(*area) +
                        " (part of the surface lies inside another solid or outside the fluid "
                        "body?); the flux uses the layer's estimate " +
                        format_number(s.layer_area));
      s = surface_share(ctx.scene.particles, geo.surface_id, geo.surface_distance, body->surface_id,
                        geo.spacing, std::nullopt, part);
    }
    if (!area) {
      r.warning(at, "the area of " + what + " is " + why +
                        ": the flux uses its first fluid layer's estimate " +
                        format_number(s.layer_area) +
                        ", accurate to about a spacing over the surface's radius of curvature; "
                        "for an exact area use a primitive or a mesh wholly inside the box");
    }
    if (region) {  // the part of the layer in the region, with the shares it had
      BoundaryShare kept;
      for (std::size_t k = 0; k < s.particles.size(); ++k) {
        const auto& in = region->particles;
        if (!std::binary_search(in.begin(), in.end(), s.particles[k])) continue;
        kept.particles.push_back(s.particles[k]);
        kept.areas.push_back(s.areas[k]);
        kept.area += s.areas[k];
      }
      if (kept.particles.empty()) {
        r.error(rf, "boundary flux '" + rx.name +
                        "': no particle of the first fluid layer next "
                        "to " +
                        what + " lies in region '" + region->name +
                        "'; allowed: a region that holds part of that layer");
        return false;
      }
      s = std::move(kept);
    }
    rx.boundary_particles = std::move(s.particles);
    rx.boundary_areas = std::move(s.areas);
  } catch (const InvalidArgument& e) {
    r.error(at, "boundary flux '" + rx.name + "' on " + (group ? what : "surface " + what) + ": " +
                    e.what());
    return false;
  }
  return true;
}

}  // namespace sadr::orchestrator::detail
