// SPDX-License-Identifier: MIT
#include "sadr/fluid/stability.hpp"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>

#include "sadr/common/log.hpp"
#include "sadr/common/status.hpp"

namespace sadr::fluid {

namespace {

/// Whether this is the first call for the limit `name` with this `said` set (one bit per limit
/// name: once per process).
bool first_time(std::atomic<unsigned>& said, const std::string& name) {
  const char* names[] = {"acoustic", "viscous", "body_force", "diffusion", "reaction"};
  unsigned bit = 1;
  while (bit < (1u << 5) && name != names[std::countr_zero(bit)]) bit <<= 1;
  return !(said.fetch_or(bit) & bit);
}

}  // namespace

bool warn_forced_substep(const StabilityLimits& limits, double dt) {
  const auto [limit, name] = limits.smallest();
  static std::atomic<unsigned> said{0};
  if (!(dt > limit) || !first_time(said, name)) return false;
  char text[160];
  std::snprintf(text, sizeof text,
                "force_time_step: sub-step %.4g is %.3gx the %s stability limit ", dt, dt / limit,
                name.c_str());
  log::warn(std::string(text) + format_value(limit) +
            "; the results may be wrong without any non-finite value (said once per limit)");
  return true;
}

bool warn_unbinding_cap(const StabilityLimits& limits, double max_time_step) {
  const auto [limit, name] = limits.smallest();
  static std::atomic<unsigned> said{0};
  if (!(max_time_step > limit) || !first_time(said, name)) return false;
  log::warn("max_time_step " + format_value(max_time_step) + " is above the " + name +
            " stability limit " + format_value(limit) +
            "; the sub-steps follow the limit (max_time_step is an upper bound; force_time_step "
            "takes it as the sub-step). Said once per limit.");
  return true;
}

SubstepBound substep_bound(const StabilityLimits& limits, double max_time_step, bool force) {
  SubstepBound b;
  std::tie(b.limit, b.limit_name) = limits.smallest();
  b.dt = b.limit;
  b.criterion = b.limit_name;
  if (max_time_step > 0 && (force || max_time_step < b.limit)) {
    b.dt = max_time_step;
    b.criterion = "max_time_step";
  }
  return b;
}

Substep next_substep(const StabilityLimits& limits, double max_time_step, bool force,
                     double remaining, double& stable_dt, std::string& criterion) {
  const SubstepBound bound = substep_bound(limits, max_time_step, force);
  Substep out{0.0, bound.limit, bound.limit_name};
  if (out.limit < stable_dt) {
    stable_dt = out.limit;
    criterion = out.limit_name;
  }
  if (max_time_step > 0) {
    if (force) warn_forced_substep(limits, std::min(max_time_step, remaining));
    if (!force) warn_unbinding_cap(limits, std::min(max_time_step, remaining));
  }
  const double allowed = bound.dt;
  const double n = std::ceil(remaining / allowed * (1.0 - 1e-12));
  out.dt = (std::isfinite(n) && n > 1) ? remaining / n : remaining;
  return out;
}

UniformSubsteps uniform_substeps(const StabilityLimits& limits, double max_time_step, bool force,
                                 double time_step) {
  const SubstepBound bound = substep_bound(limits, max_time_step, force);
  UniformSubsteps out;
  out.limit = bound.limit;
  out.limit_name = bound.limit_name;
  if (max_time_step > 0.0) {
    if (force) warn_forced_substep(limits, max_time_step);
    if (!force) warn_unbinding_cap(limits, max_time_step);
  }
  const double dt_max = bound.dt;
  out.count =
      static_cast<std::uint32_t>(std::max(1.0, std::ceil(time_step / dt_max * (1.0 - 1e-12))));
  out.dt = time_step / out.count;
  return out;
}

}  // namespace sadr::fluid
