// SPDX-License-Identifier: MIT
// Scene section "fluid": backend name and its parameters.
#include <array>
#include <cmath>

#include "scene_parts.hpp"

namespace sadr::orchestrator::detail {

namespace {
constexpr std::array<std::string_view, 14> kFluidKeys{
    "backend",     "smoothing_length", "h_over_dx",       "kernel",    "reference_density",
    "sound_speed", "shear_viscosity",  "temperature",     "gravity",   "density_mode",
    "boussinesq",  "max_time_step",    "force_time_step", "parameters"};
constexpr std::array<std::string_view, 3> kBackends{"sdpd", "static", "tdpd"};
constexpr std::array<std::string_view, 1> kKernels{"lucy"};
constexpr std::array<std::string_view, 2> kDensityModes{"continuity", "summation"};
constexpr std::array<std::string_view, 4> kBoussinesqKeys{"species", "coefficient", "reference",
                                                          "direction"};

void read_boussinesq(SceneContext& ctx, const Field& fluid) {
  YamlReader& r = ctx.reader;
  const Field b = YamlReader::child(fluid, "boussinesq");
  if (!YamlReader::present(b) || !r.expect_map(b, kBoussinesqKeys)) return;
  Boussinesq out;
  out.species = r.string(b, "species", true).value_or("");
  out.coefficient =
      r.number(b, "coefficient", Bound::kAny, "length^(d+2)/(time^2 molecules)", true).value_or(0);
  out.reference = r.number_or(b, "reference", 0.0, Bound::kNonNegative, "molecules/length^d");
  const int d = ctx.scene.box.dimension;
  if (d == 1) out.direction = {1.0, 0.0, 0.0};
  if (auto dir =
          ctx.dimension_ok ? r.vector(b, "direction", d, "dimensionless", false) : std::nullopt) {
    const double norm =
        std::sqrt((*dir)[0] * (*dir)[0] + (*dir)[1] * (*dir)[1] + (*dir)[2] * (*dir)[2]);
    if (!(norm > 0.0)) {
      r.error(YamlReader::child(b, "direction"),
              "the zero vector is not allowed; allowed: a "
              "non-zero vector (it is normalised)");
    } else {
      for (auto& c : *dir) c /= norm;
      out.direction = *dir;
    }
  }
  ctx.scene.fluid.boussinesq = out;
  ctx.boussinesq = b;
}

}  // namespace

void read_fluid(SceneContext& ctx, const Field& root) {
  YamlReader& r = ctx.reader;
  FluidSettings& fl = ctx.scene.fluid;
  const Field f = YamlReader::child(root, "fluid");
  if (!YamlReader::present(f)) {
    r.error(f, "missing; required: a map with at least 'backend' and the smoothing length");
    return;
  }
  if (!r.expect_map(f, kFluidKeys)) return;
  const auto backend = r.choice(f, "backend", kBackends, true, "fluid backend");
  if (backend) fl.backend = *backend;
  const auto h = r.number(f, "smoothing_length", Bound::kPositive, "length", false);
  ctx.h_over_dx = r.number(f, "h_over_dx", Bound::kPositive, "dimensionless", false);
  if (h && ctx.h_over_dx) {
    r.error(YamlReader::child(f, "h_over_dx"),
            "give either smoothing_length or h_over_dx, not both");
    ctx.h_over_dx.reset();
  }
  if (h) fl.smoothing_length = *h;
  if (!h && !ctx.h_over_dx && !YamlReader::present(YamlReader::child(f, "smoothing_length")) &&
      !YamlReader::present(YamlReader::child(f, "h_over_dx"))) {
    r.error(YamlReader::child(f, "smoothing_length"),
            "missing; required: smoothing_length (a number > 0 [length]) or h_over_dx (> 0)");
  }
  if (auto k = r.choice(f, "kernel", kKernels, false, "kernel")) fl.kernel = *k;
  fl.reference_density =
      r.number_or(f, "reference_density", 1.0, Bound::kPositive, "mass/length^d");
  const bool sdpd = backend && *backend == "sdpd";  // unknown backend: no follow-up errors
  fl.sound_speed = r.number(f, "sound_speed", Bound::kPositive, "length/time", sdpd).value_or(0);
  fl.shear_viscosity =
      r.number(f, "shear_viscosity", Bound::kNonNegative, "mass/(length^(d-2) time)", sdpd)
          .value_or(0);
  fl.temperature = r.number_or(f, "temperature", 0.0, Bound::kNonNegative, "energy");
  if (ctx.dimension_ok) {
    if (auto g = r.vector(f, "gravity", ctx.scene.box.dimension, "length/time^2", false)) {
      fl.gravity = *g;
    }
  }
  if (auto m = r.choice(f, "density_mode", kDensityModes, false, "density mode")) {
    fl.density_mode = *m;
  }
  fl.max_time_step = r.number_or(f, "max_time_step", 0.0, Bound::kNonNegative, "time");
  fl.force_time_step = r.boolean(f, "force_time_step", false).value_or(false);
  const Field params = YamlReader::child(f, "parameters");
  if (YamlReader::present(params)) {
    if (!params.node.IsMap()) {
      r.error(params, "expected a map of name: number (backend-specific parameters)");
    } else {
      for (const auto& kv : params.node) {
        const std::string key = kv.first.Scalar();
        if (auto v = r.number(params, key, Bound::kAny, "", true)) fl.parameters[key] = *v;
      }
    }
  }
  read_boussinesq(ctx, f);
}

}  // namespace sadr::orchestrator::detail
