// SPDX-License-Identifier: MIT
// Scene section "geometry" in a build without the geometry library (-DSADR_WITH_GEOMETRY=OFF).
#include "sadr/common/status.hpp"
#include "sadr/orchestrator/scene_geometry.hpp"
#include "scene_parts.hpp"

namespace sadr::orchestrator {
namespace detail {

void read_geometry(SceneContext& ctx, const Field& root) {
  ctx.reader.error(YamlReader::child(root, "geometry"),
                   "this sadr was built without the geometry library (-DSADR_WITH_GEOMETRY=OFF); "
                   "allowed: 'particles' (a lattice with fill rules, or a particle file)");
}

}  // namespace detail

GeometryDensityError geometry_density_error(const Scene&) {
  throw InvalidArgument("this sadr was built without the geometry library");
}

}  // namespace sadr::orchestrator
