// SPDX-License-Identifier: MIT
#include "sadr/fluid/stability.hpp"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdio>
#include <tuple>

#include "sadr/common/log.hpp"
#include "sadr/common/status.hpp"

namespace sadr::fluid {

void StabilityLimits::check(double dt) const {
  // Name the tightest limit dt breaks (the binding one), not the first one listed.
  struct Rule {
    double limit;
    const char* name;
    const char* formula;
  };
  const Rule rules[] = {
      {acoustic, "acoustic", "0.25 (h/2)/(c0 + v_max)"},
      {viscous, "viscous", "min(0.125 rho (h/2)^2/eta, Gershgorin bound)"},
      {body_force, "body_force", "0.25 sqrt((h/2)/|a|)"},
      {diffusion, "diffusion", "min(0.125 (h/2)^2/kappa, Gershgorin bound of the SPH Laplacian)"},
      {reaction, "reaction", "1/|reaction Jacobian|"}};
  const Rule* worst = nullptr;
  for (const Rule& r : rules) {
    if (dt > r.limit && (!worst || r.limit < worst->limit)) worst = &r;
  }
  if (!worst) return;
  throw InvalidArgument(std::string("time step ") + format_value(dt) + " breaks the " +
                            worst->name + " stability limit " + format_value(worst->limit) + " (" +
                            worst->formula + "); reduce max_time_step or set force_time_step",
                        {{"limit", worst->name},
                         {"limit_value", format_value(worst->limit)},
                         {"dt", format_value(dt)}});
}

bool warn_forced_substep(const StabilityLimits& limits, double dt) {
  const auto [limit, name] = limits.smallest();
  if (!(dt > limit)) return false;
  static std::atomic<unsigned> warned{0};  // one bit per limit name: once per process
  const char* names[] = {"acoustic", "viscous", "body_force", "diffusion", "reaction"};
  unsigned bit = 1;
  while (bit < (1u << 5) && name != names[std::countr_zero(bit)]) bit <<= 1;
  if (warned.fetch_or(bit) & bit) return false;
  char text[200];
  std::snprintf(text, sizeof text,
                "force_time_step: sub-step %.4g is %.3gx the %s stability limit %.4g; the results "
                "may be wrong without any non-finite value (said once per limit)",
                dt, dt / limit, name.c_str(), limit);
  log::warn(text);
  return true;
}

Substep next_substep(const StabilityLimits& limits, double max_time_step, bool force,
                     double remaining, double& stable_dt, std::string& criterion) {
  Substep out;
  std::tie(out.limit, out.limit_name) = limits.smallest();
  if (out.limit < stable_dt) {
    stable_dt = out.limit;
    criterion = out.limit_name;
  }
  double allowed = out.limit;
  if (max_time_step > 0) {
    if (!force) limits.check(std::min(max_time_step, remaining));
    if (force) warn_forced_substep(limits, std::min(max_time_step, remaining));
    allowed = max_time_step;
  }
  const double n = std::ceil(remaining / allowed * (1.0 - 1e-12));
  out.dt = (std::isfinite(n) && n > 1) ? remaining / n : remaining;
  return out;
}

UniformSubsteps uniform_substeps(const StabilityLimits& limits, double max_time_step, bool force,
                                 double time_step) {
  UniformSubsteps out;
  std::tie(out.limit, out.limit_name) = limits.smallest();
  double dt_max = out.limit;
  if (max_time_step > 0.0) {
    if (!force) limits.check(max_time_step);
    if (force) warn_forced_substep(limits, max_time_step);
    dt_max = force ? max_time_step : std::min(out.limit, max_time_step);
  }
  out.count =
      static_cast<std::uint32_t>(std::max(1.0, std::ceil(time_step / dt_max * (1.0 - 1e-12))));
  out.dt = time_step / out.count;
  return out;
}

}  // namespace sadr::fluid
