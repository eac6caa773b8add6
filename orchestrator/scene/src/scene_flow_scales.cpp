// SPDX-License-Identifier: MIT
// The flow's scales before the run (docs/scene-format.md, "Sound speed and background pressure"):
// the largest speed and the pressure variation a scene implies, from what drives its fluid
// (gravity, an open boundary's inflow, moving walls, initial velocities), and whether a body
// stands in the flow. From them the loader chooses the sound speed a scene leaves out, and a
// background pressure around an obstacle, and warns where given settings break the rules.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <unordered_map>
#include <vector>

#include "sadr/fluid/backend_schema.hpp"
#include "scene_parts.hpp"

namespace sadr::orchestrator::detail {
namespace {

constexpr double kDensityVariation = 0.01;  ///< delta: |rho/rho0 - 1| the sound speed allows
constexpr double kMachFactor = 10.0;        ///< c0 >= 10 U (Mach 0.1)
constexpr double kMaxCompression = 1.05;    ///< a chosen background pressure: rho/rho0 <= this
constexpr std::array<char, 3> kAxisNames{'x', 'y', 'z'};

struct Scales {
  double rho = 0;            ///< the fluid's density (median over fluid particles)
  double speed = 0;          ///< the largest flow speed expected
  std::string speed_from;    ///< what sets it
  bool speed_bound = false;  ///< `speed` is an upper bound (Poiseuille without the obstacles)
  double drop = 0;           ///< the pressure variation expected
  std::string drop_from;
  std::string obstacle;  ///< "" or what stands in the flow
};

/// A figure for a message: 4 significant digits.
std::string num(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.4g", x);
  return b;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

/// Extent of the fluid particles along `axis`, plus one spacing (the no-slip planes lie half a
/// spacing beyond the outer rows).
double fluid_extent(const Scene& s, int axis, double dx) {
  const ParticleState& p = s.particles;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kind(i) != ParticleKind::kFluid) continue;
    const double x = p.positions[3 * i + static_cast<std::size_t>(axis)];
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  return hi >= lo ? hi - lo + dx : 0.0;
}

/// A connected set of wall particles (neighbours closer than 1.5 dx) that reaches no walled face
/// of the box: a body in the flow. Geometry scenes name theirs (solid bodies).
std::string find_obstacle(const Scene& s, double dx) {
  if (s.geometry) {
    for (const auto& b : s.geometry->bodies) {
      if (b.role == "solid") return "the solid body '" + b.name + "'";
    }
    return "";
  }
  const ParticleState& p = s.particles;
  const int d = s.box.dimension;
  std::vector<std::uint32_t> walls;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kind(i) == ParticleKind::kWall) walls.push_back(static_cast<std::uint32_t>(i));
  }
  if (walls.empty() || !(dx > 0)) return "";
  const double cell = 1.5 * dx;
  auto key = [&](std::uint32_t i, const std::array<long, 3>& off) {
    std::uint64_t k = 1469598103934665603ULL;
    for (int a = 0; a < 3; ++a) {
      const long c =
          a < d ? static_cast<long>(std::floor(p.positions[3 * i + a] / cell)) + off[a] : 0;
      k = (k ^ static_cast<std::uint64_t>(c)) * 1099511628211ULL;
    }
    return k;
  };
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> grid;
  for (const auto i : walls) grid[key(i, {0, 0, 0})].push_back(i);
  std::vector<char> seen(p.size(), 0);
  auto touches_face = [&](std::uint32_t i) {
    for (int a = 0; a < d; ++a) {
      if (s.box.periodic[a]) continue;
      const double x = p.positions[3 * i + a];
      if (x - s.box.lo[a] < cell || s.box.hi[a] - x < cell) return true;
    }
    return false;
  };
  for (const auto start : walls) {
    if (seen[start]) continue;
    std::vector<std::uint32_t> stack{start};
    seen[start] = 1;
    bool reaches_face = false;
    std::size_t members = 0;
    std::array<double, 3> centre{};
    while (!stack.empty()) {
      const std::uint32_t i = stack.back();
      stack.pop_back();
      ++members;
      for (int a = 0; a < 3; ++a) centre[a] += p.positions[3 * i + a];
      reaches_face = reaches_face || touches_face(i);
      for (long ox = -1; ox <= 1; ++ox) {
        for (long oy = d > 1 ? -1 : 0; oy <= (d > 1 ? 1 : 0); ++oy) {
          for (long oz = d > 2 ? -1 : 0; oz <= (d > 2 ? 1 : 0); ++oz) {
            const auto it = grid.find(key(i, {ox, oy, oz}));
            if (it == grid.end()) continue;
            for (const auto j : it->second) {
              if (seen[j]) continue;
              double r2 = 0;
              for (int a = 0; a < d; ++a) {
                const double dd = p.positions[3 * j + a] - p.positions[3 * i + a];
                r2 += dd * dd;
              }
              if (r2 < cell * cell) {
                seen[j] = 1;
                stack.push_back(j);
              }
            }
          }
        }
      }
    }
    if (!reaches_face) {
      std::string at = "(";
      for (int a = 0; a < d; ++a) {
        at += (a > 0 ? ", " : "") + num(centre[a] / static_cast<double>(members));
      }
      return std::to_string(members) + " wall particles around " + at +
             ") that reach no walled face of the box";
    }
  }
  return "";
}

void raise(double& value, std::string& from, double candidate, std::string why) {
  if (candidate > value) {
    value = candidate;
    from = std::move(why);
  }
}

Scales flow_scales(const Scene& s) {
  const ParticleState& p = s.particles;
  const FluidSettings& f = s.fluid;
  const int d = s.box.dimension;
  const double dx = s.lattice_spacing > 0 ? s.lattice_spacing : f.smoothing_length / 3.0;
  Scales out;
  std::vector<double> rho;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kind(i) == ParticleKind::kFluid) rho.push_back(p.densities[i]);
  }
  out.rho = median(std::move(rho));
  if (!(out.rho > 0)) out.rho = f.reference_density;
  const double nu = f.shear_viscosity / out.rho;
  out.obstacle = find_obstacle(s, dx);
  for (int a = 0; a < d; ++a) {  // gravity: its pressure over a height, or over a period onto a
    const double g = std::abs(f.gravity[a]);  // body in the flow; a channel's speed
    if (!(g > 0)) continue;
    const double length = s.box.periodic[a] ? s.box.length(a) : fluid_extent(s, a, dx);
    const std::string axis(1, kAxisNames[a]);
    if (!s.box.periodic[a] || !out.obstacle.empty()) {
      raise(out.drop, out.drop_from, out.rho * g * length,
            "rho |g_" + axis + "| L_" + axis + " = " + num(out.rho) + " x " + num(g) + " x " +
                num(length));
    }
    if (!s.box.periodic[a] || !(nu > 0)) continue;
    double width = std::numeric_limits<double>::infinity();  // the narrowest walled extent across
    for (int b = 0; b < d; ++b) {
      if (b != a && !s.box.periodic[b]) width = std::min(width, fluid_extent(s, b, dx));
    }
    if (!std::isfinite(width)) continue;  // nothing holds it back: no speed to estimate
    const double u = g * width * width / (8.0 * nu);
    if (u > out.speed) {
      out.speed = u;
      out.speed_bound = true;
      out.speed_from = "plane Poiseuille flow driven by g_" + axis + " between walls " +
                       num(width) + " apart, g H^2 / (8 nu)";
    }
  }
  if (const auto& ob = f.open_boundary) {
    const double umax = ob->mean_velocity * (ob->parabolic ? 1.5 : 1.0);
    if (umax > out.speed) {
      out.speed = umax;
      out.speed_bound = false;
      out.speed_from = "the open boundary's inflow";
    }
    double drop = 0.5 * out.rho * umax * umax;
    if (ob->parabolic && ob->wall_hi > ob->wall_lo) {
      const double width = ob->wall_hi - ob->wall_lo;
      drop += 8.0 * f.shear_viscosity * umax * (ob->outlet_hi - ob->inlet_lo) / (width * width);
    }
    raise(out.drop, out.drop_from, drop, "the open channel: rho U^2 / 2 plus its viscous drop");
  }
  double vmax = 0;  // moving walls and initial velocities
  bool wall = false;
  for (std::size_t i = 0; i < p.size() && !p.velocities.empty(); ++i) {
    double v2 = 0;
    for (int a = 0; a < d; ++a) v2 += p.velocities[3 * i + a] * p.velocities[3 * i + a];
    if (std::sqrt(v2) > vmax) {
      vmax = std::sqrt(v2);
      wall = p.kind(i) == ParticleKind::kWall;
    }
  }
  if (vmax > out.speed || (vmax > 0 && out.speed_bound)) {
    out.speed = std::max(vmax, out.speed_bound ? 0.0 : out.speed);
    out.speed_bound = false;
    out.speed_from = wall ? "the moving walls" : "the initial velocities";
  }
  raise(out.drop, out.drop_from, out.rho * vmax * vmax,
        wall ? "rho U^2 of the moving walls" : "rho U^2 of the initial velocities");
  return out;
}

/// Two significant digits, rounded up.
double round_up(double x) {
  const double scale = std::pow(10.0, std::floor(std::log10(x)) - 1.0);
  return std::ceil(x / scale * (1 - 1e-12)) * scale;
}

/// Tait pressure at density rho for reference rho0 and sound speed c0 (gamma = 7).
double tait(double rho, double rho0, double c0) {
  return rho0 * c0 * c0 / 7.0 * (std::pow(rho / rho0, 7.0) - 1.0);
}

}  // namespace

void choose_flow_settings(SceneContext& ctx, const Field& root, bool sound_speed_given,
                          bool reference_density_given) {
  Scene& s = ctx.scene;
  FluidSettings& f = s.fluid;
  const Field fluid = YamlReader::child(root, "fluid");
  const Field backend = YamlReader::child(fluid, "backend");  // as written: an unknown one is
  if (!backend.node.IsScalar()) return;                       // an error already
  const auto* spec = sadr::fluid::schema::find(backend.node.Scalar());
  if (!ctx.particles_ok || spec == nullptr || !spec->needs("sound_speed")) return;
  YamlReader& r = ctx.reader;
  const Scales sc = flow_scales(s);
  const double c_drop = std::sqrt(sc.drop / (sc.rho * kDensityVariation));
  const double c_mach = kMachFactor * sc.speed;
  const std::string drop_text =
      "the expected pressure variation " + num(sc.drop) + " (" + sc.drop_from + ")";
  if (!sound_speed_given) {
    const double c0 = std::max(c_drop, c_mach);
    if (!(c0 > 0) || !std::isfinite(c0)) {
      r.error(YamlReader::child(fluid, "sound_speed"),
              "missing, and nothing in the scene sets a flow speed or a pressure variation to "
              "choose it from (no gravity, open boundary, moving wall or initial velocity); give "
              "sound_speed (> 0 [length/time], at least 10x the largest flow speed)");
      return;
    }
    f.sound_speed = round_up(c0);
    std::string why = "sound speed c0 = " + num(f.sound_speed) + " (fluid.sound_speed " +
                      "left out): the largest of 10 U = " + num(c_mach);
    if (sc.speed > 0) {
      why += " (U " + std::string(sc.speed_bound ? "<= " : "= ") + num(sc.speed) + ", " +
             sc.speed_from + ")";
    }
    why += " and sqrt(dp / (0.01 rho)) = " + num(c_drop);
    if (sc.drop > 0) why += " (dp = " + num(sc.drop) + ", " + sc.drop_from + ")";
    s.chosen.push_back(why);
  } else {
    const Field c = YamlReader::child(fluid, "sound_speed");
    if (f.sound_speed < c_drop * (1 - 1e-9)) {
      r.warning(c, "c0 = " + num(f.sound_speed) +
                       " is below sqrt(dp / (0.01 rho)) = " + num(c_drop) + " for " + drop_text +
                       ": the density will vary by more than 1 % and fluid can be pressed "
                       "between wall particles; use sound_speed >= " +
                       num(round_up(c_drop)) + " or leave it out to have it chosen");
    } else if (!sc.speed_bound && f.sound_speed < c_mach * (1 - 1e-9)) {
      r.warning(c, "c0 = " + num(f.sound_speed) + " is below 10 U = " + num(c_mach) +
                       " (U = " + num(sc.speed) + ", " + sc.speed_from +
                       "): Mach number above 0.1; use sound_speed >= " + num(round_up(c_mach)));
    }
  }
  if (sc.obstacle.empty() || !(sc.drop > 0)) return;
  if (f.open_boundary) {  // its outlet holds rho0: the fluid relaxes to it, the shift is lost
    if (!reference_density_given) {
      s.chosen.push_back(
          "background pressure: none (a body stands in the flow, but the open "
          "boundary's outlet holds the reference density, so the fluid would "
          "relax to it)");
    }
    return;
  }
  const double c0 = f.sound_speed;
  if (reference_density_given) {
    const double pb = tait(sc.rho, f.reference_density, c0);
    if (pb < sc.drop * (1 - 1e-9)) {
      r.warning(YamlReader::child(fluid, "reference_density"),
                "a body stands in the flow (" + sc.obstacle + ") and the background pressure " +
                    num(pb) + " (the Tait pressure at the fluid's density " + num(sc.rho) +
                    ") is below " + drop_text +
                    ": the pressure behind the body can go negative, leaving a void in the wake "
                    "and drawing fluid between its wall particles; lower reference_density (or "
                    "leave it out to have a background pressure chosen)");
    }
    return;
  }
  // The background pressure p_b = dp: rho0 = rho / t with rho0 c0^2 / 7 (t^7 - 1) = dp, t capped.
  double lo = 1.0, hi = kMaxCompression;
  if (tait(sc.rho, sc.rho / hi, c0) >= sc.drop) {
    for (int k = 0; k < 100; ++k) {
      const double mid = 0.5 * (lo + hi);
      (tait(sc.rho, sc.rho / mid, c0) < sc.drop ? lo : hi) = mid;
    }
  }
  f.reference_density = sc.rho / hi;
  const double pb = tait(sc.rho, f.reference_density, c0);
  s.chosen.push_back("background pressure " + num(pb) + ": reference_density " +
                     num(f.reference_density) + " below the fluid's density " + num(sc.rho) +
                     " (fluid.reference_density left out; a body stands " +
                     "in the flow: " + sc.obstacle + "; " + drop_text + ")" +
                     (pb < sc.drop * (1 - 1e-9) ? "; capped at rho / rho0 = 1.05, raise the "
                                                  "sound speed for the full value"
                                                : ""));
}

}  // namespace sadr::orchestrator::detail
