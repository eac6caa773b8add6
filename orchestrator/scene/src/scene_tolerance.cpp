// SPDX-License-Identifier: MIT
// Scene key time.tolerance: the coupling step chosen by an error controller
// (docs/method.md section 1b, docs/scene-format.md "time").
#include <array>

#include "scene_parts.hpp"

namespace sadr::orchestrator::detail {

namespace {
constexpr std::array<std::string_view, 3> kToleranceKeys{"relative", "absolute", "max_step"};
}  // namespace

void read_time_tolerance(SceneContext& ctx, const Field& time) {
  YamlReader& r = ctx.reader;
  Scene& s = ctx.scene;
  const Field f = YamlReader::child(time, "tolerance");
  if (!YamlReader::present(f)) return;
  StepTolerance tol;
  tol.max_step = s.time.coupling_step;
  if (f.node.IsScalar()) {  // a number: the relative tolerance
    const auto rel = r.number_at(f, Bound::kPositive, "relative tolerance");
    if (!rel) return;
    tol.relative = *rel;
  } else if (f.node.IsMap()) {
    if (!r.expect_map(f, kToleranceKeys)) return;
    const auto rel = r.number(f, "relative", Bound::kNonNegative, "relative tolerance", false);
    const auto abs = r.number(f, "absolute", Bound::kNonNegative, "input units", false);
    const auto max = r.number(f, "max_step", Bound::kPositive, "time", false);
    if (YamlReader::present(YamlReader::child(f, "relative")) && !rel) return;
    if (YamlReader::present(YamlReader::child(f, "absolute")) && !abs) return;
    if (YamlReader::present(YamlReader::child(f, "max_step")) && !max) return;
    tol.relative = rel.value_or(0.0);
    tol.absolute = abs.value_or(0.0);
    if (!(tol.relative > 0.0 || tol.absolute > 0.0)) {
      r.error(f, "relative " + format_number(tol.relative) + " and absolute " +
                     format_number(tol.absolute) +
                     " are both 0; allowed: relative > 0 or absolute > 0 (a zero tolerance "
                     "cannot be met)");
      return;
    }
    if (max) {
      if (*max < s.time.coupling_step) {
        r.error(YamlReader::child(f, "max_step"),
                format_number(*max) + " is below time.coupling_step " +
                    format_number(s.time.coupling_step) +
                    " (the first step); allowed: max_step >= coupling_step");
        return;
      }
      tol.max_step = *max;
    }
  } else {
    r.error(f,
            "expected a number (the relative tolerance, > 0) or a map with relative, "
            "absolute, max_step");
    return;
  }
  if (tol.relative >= 1.0) {
    r.error(f.node.IsMap() ? YamlReader::child(f, "relative") : f,
            format_number(tol.relative) +
                " is not a tolerance; allowed: 0 <= relative < 1 (1e-3 asks for 0.1 %)");
    return;
  }
  s.time.tolerance = tol;
}

}  // namespace sadr::orchestrator::detail
