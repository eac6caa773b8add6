// SPDX-License-Identifier: MIT
// Prescribed wall velocities: a solid body's `motion`, a wall fill rule's `velocity`, and the
// checks that the motion keeps the wall's particles on its surface (scene_wall_motion.hpp).
#include "scene_wall_motion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "sadr/fluid/backend_schema.hpp"
#include "sadr/orchestrator/hash.hpp"

namespace sadr::orchestrator::detail {

namespace {

constexpr std::array<std::string_view, 5> kMotionKeys{"velocity", "angular_velocity", "center",
                                                      "axis", "moves"};

double norm(const std::array<double, 3>& v) {
  return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

std::string vector_text(const std::array<double, 3>& v, int d) {
  std::string out = "(";
  for (int a = 0; a < d; ++a) {
    out += (a > 0 ? ", " : "") + format_number(v[static_cast<std::size_t>(a)]);
  }
  return out + ")";
}

}  // namespace

std::array<double, 3> WallMotion::at(const double* x) const {
  const std::array<double, 3> r{x[0] - center[0], x[1] - center[1], x[2] - center[2]};
  const double w = angular_velocity;
  return {velocity[0] + w * (axis[1] * r[2] - axis[2] * r[1]),
          velocity[1] + w * (axis[2] * r[0] - axis[0] * r[2]),
          velocity[2] + w * (axis[0] * r[1] - axis[1] * r[0])};
}

std::optional<WallMotion> read_wall_motion(SceneContext& ctx, const Field& parent) {
  YamlReader& r = ctx.reader;
  const Field f = YamlReader::child(parent, "motion");
  if (!YamlReader::present(f) || !ctx.dimension_ok) return std::nullopt;
  if (!r.expect_map(f, kMotionKeys)) return std::nullopt;
  const int d = ctx.scene.box.dimension;
  WallMotion m;
  if (auto v = r.vector(f, "velocity", d, "length/time", false)) m.velocity = *v;
  m.angular_velocity = r.number_or(f, "angular_velocity", 0.0, Bound::kAny, "1/time");
  const bool spins = YamlReader::present(YamlReader::child(f, "angular_velocity"));
  if (auto c = r.vector(f, "center", d, "length", spins)) m.center = *c;
  const Field af = YamlReader::child(f, "axis");
  if (YamlReader::present(af) && d != 3) {
    r.error(af, "'axis' applies in 3D; in 2D a body spins about z");
  } else if (auto a = r.vector(f, "axis", 3, "-", false)) {
    const double len = norm(*a);
    if (!(len > 0)) {
      r.error(af, "the axis has length 0; allowed: a non-zero vector");
    } else {
      for (std::size_t k = 0; k < 3; ++k) m.axis[k] = (*a)[k] / len;
    }
  }
  if (!spins && !YamlReader::present(YamlReader::child(f, "velocity"))) {
    r.error(f, "an empty motion; required: 'velocity' and/or 'angular_velocity' (with 'center')");
  }
  if (!spins && (YamlReader::present(af) || YamlReader::present(YamlReader::child(f, "center")))) {
    r.error(f, "'center' and 'axis' describe a rotation; required with them: 'angular_velocity'");
  }
  if (auto moves = r.boolean(f, "moves", false)) m.moves = *moves;
  // Morris walls made by the geometry extrapolate across each wall particle's own tangent plane,
  // which travels with it; wall_planes' surfaces stay in place and the planes do not turn.
  if (m.moves && ctx.scene.fluid.wall_model == "morris" &&
      (spins || !ctx.scene.fluid.wall_planes.empty())) {
    r.error(YamlReader::child(f, "moves"),
            std::string("a moving body with fluid.wall_model morris ") +
                (spins ? "that turns (Morris' tangent planes do not turn)"
                       : "and fluid.wall_planes (their surfaces stay in place)") +
                "; allowed with moves: true: wall_model stationary or adami, or morris for a "
                "body that only translates, without wall_planes");
  }
  require_moving_walls(ctx, f);
  return m;
}

bool backend_moves_walls(const SceneContext& ctx) {
  const auto* b = sadr::fluid::schema::find(ctx.scene.fluid.backend);
  return b == nullptr || b->capabilities.moving_walls;
}

void require_moving_walls(SceneContext& ctx, const Field& where) {
  if (backend_moves_walls(ctx)) return;
  ctx.reader.error(where, "the fluid backend '" + ctx.scene.fluid.backend +
                              "' keeps wall particles at rest (no moving walls); allowed with: "
                              "sdpd");
}

void check_face_wall_motion(SceneContext& ctx, const Field& where, const std::array<double, 3>& v,
                            const std::vector<std::uint32_t>& members) {
  const ParticleState& p = ctx.scene.particles;
  const int d = ctx.scene.box.dimension;
  constexpr double inf = std::numeric_limits<double>::infinity();
  for (int a = 0; a < d; ++a) {
    const auto ua = static_cast<std::size_t>(a);
    if (ctx.scene.box.periodic[ua] || v[ua] == 0.0 || members.empty()) continue;
    double fluid_lo = inf, fluid_hi = -inf, wall_lo = inf, wall_hi = -inf;
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.kind(i) != ParticleKind::kFluid) continue;
      fluid_lo = std::min(fluid_lo, p.positions[3 * i + ua]);
      fluid_hi = std::max(fluid_hi, p.positions[3 * i + ua]);
    }
    for (const std::uint32_t i : members) {
      wall_lo = std::min(wall_lo, p.positions[3 * i + ua]);
      wall_hi = std::max(wall_hi, p.positions[3 * i + ua]);
    }
    if (wall_lo > fluid_hi || wall_hi < fluid_lo) {
      ctx.reader.error(where, "the wall velocity " + vector_text(v, d) + " has a component " +
                                  format_number(v[ua]) + " along axis " +
                                  std::string(1, static_cast<char>('x' + a)) +
                                  ", normal to the wall (its particles lie beyond the fluid on "
                                  "that axis); allowed: a velocity along the wall (moving walls "
                                  "keep their positions)");
    }
  }
}

void apply_body_motion(SceneContext& ctx, const Field& where, const WallMotion& motion,
                       const std::vector<std::uint32_t>& members,
                       const std::vector<std::array<double, 3>>& normals) {
  ParticleState& p = ctx.scene.particles;
  const int d = ctx.scene.box.dimension;
  double vmax = 0.0;
  std::vector<std::array<double, 3>> v(members.size());
  for (std::size_t k = 0; k < members.size(); ++k) {
    v[k] = motion.at(&p.positions[3 * members[k]]);
    for (int a = d; a < 3; ++a) v[k][static_cast<std::size_t>(a)] = 0.0;
    vmax = std::max(vmax, norm(v[k]));
  }
  for (std::size_t k = 0; k < members.size(); ++k) {
    const std::uint32_t i = members[k];
    const auto& n = normals[i];
    const double vn = n[0] * v[k][0] + n[1] * v[k][1] + n[2] * v[k][2];
    if (!motion.moves && std::abs(vn) > 1e-6 * vmax) {
      const std::array<double, 3> x{p.positions[3 * i], p.positions[3 * i + 1],
                                    p.positions[3 * i + 2]};
      ctx.reader.error(
          where, "the motion moves the wall particle at " + vector_text(x, d) + " with " +
                     vector_text(v[k], d) + ", " + format_number(vn) +
                     " of it along the surface normal " + vector_text(n, d) +
                     "; allowed: a motion along the surface everywhere (a body "
                     "that slides along itself or spins about its own axis; a body whose walls "
                     "follow the motion: moves: true)");
      return;
    }
    for (std::size_t a = 0; a < 3; ++a) p.velocities[3 * i + a] = v[k][a];
  }
}

}  // namespace sadr::orchestrator::detail
