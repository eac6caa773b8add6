// SPDX-License-Identifier: MIT
// Scene key fluid.body_forces (docs/scene-format.md "fluid"): the regions of wall particles (a
// solid body of `geometry`, or any region that holds wall particles) whose hydrodynamic force and
// torque the fluid reports. Read after the regions and particles (check_body_forces).
#include <algorithm>
#include <string>

#include "sadr/fluid/backend_schema.hpp"
#include "scene_parts.hpp"

namespace sadr::orchestrator::detail {

void check_body_forces(SceneContext& ctx, const Field& root) {
  YamlReader& r = ctx.reader;
  const Field fluid = YamlReader::child(root, "fluid");
  const Field key = YamlReader::child(fluid, "body_forces");
  if (!YamlReader::present(key)) return;
  const auto names = r.string_list(fluid, "body_forces", false);
  if (!names) return;
  const auto* spec = sadr::fluid::schema::find(ctx.scene.fluid.backend);
  if (spec && !spec->capabilities.body_forces) {
    r.error(key, "backend " + ctx.scene.fluid.backend +
                     " does not compute forces on bodies; allowed: no body_forces (backend "
                     "sdpd computes them)");
    return;
  }
  std::vector<std::string> seen;
  for (std::size_t k = 0; k < names->size(); ++k) {
    const std::string& name = (*names)[k];
    const Field at = key.node.IsSequence() ? YamlReader::element(key, k) : key;
    if (std::find(seen.begin(), seen.end(), name) != seen.end()) {
      r.error(at, "'" + name + "' is listed twice; allowed: each body once");
      continue;
    }
    seen.push_back(name);
    const Region* region = ctx.scene.find_region(name);
    if (!region) {
      std::string known;
      for (const auto& reg : ctx.scene.regions) known += (known.empty() ? "" : ", ") + reg.name;
      r.error(at, "unknown region '" + name +
                      "' (allowed: a solid body of geometry or a region "
                      "of wall particles: " +
                      (known.empty() ? std::string("none defined") : known) + ")");
      continue;
    }
    if (!ctx.particles_ok) continue;
    const auto& s = ctx.scene.particles;
    const bool any_wall = std::any_of(
        region->particles.begin(), region->particles.end(),
        [&](std::uint32_t p) { return p < s.size() && s.kind(p) == ParticleKind::kWall; });
    if (!any_wall) {
      r.error(at, "region '" + name +
                      "' holds no wall particle; allowed: a solid body of geometry or a region "
                      "of wall particles");
      continue;
    }
  }
  ctx.scene.fluid.body_forces = seen;
}

}  // namespace sadr::orchestrator::detail
