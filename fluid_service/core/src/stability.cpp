// SPDX-License-Identifier: MIT
#include "sadr/fluid/stability.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "sadr/common/status.hpp"

namespace sadr::fluid {

void StabilityLimits::check(double dt) const {
  auto test = [&](double lim, const char* name, const char* formula) {
    if (dt > lim) {
      throw InvalidArgument(
          std::string("time step ") + format_value(dt) + " breaks the " + name +
              " stability limit " + format_value(lim) + " (" + formula +
              "); reduce max_time_step or set force_time_step",
          {{"limit", name}, {"limit_value", format_value(lim)}, {"dt", format_value(dt)}});
    }
  };
  test(acoustic, "acoustic", "0.25 (h/2)/(c0 + v_max)");
  test(viscous, "viscous", "min(0.125 rho (h/2)^2/eta, Gershgorin bound)");
  test(body_force, "body_force", "0.25 sqrt((h/2)/|a|)");
  test(diffusion, "diffusion", "min(0.125 (h/2)^2/kappa, Gershgorin bound of the SPH Laplacian)");
  test(reaction, "reaction", "1/|reaction Jacobian|");
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
    allowed = max_time_step;
  }
  const double n = std::ceil(remaining / allowed * (1.0 - 1e-12));
  out.dt = (std::isfinite(n) && n > 1) ? remaining / n : remaining;
  return out;
}

}  // namespace sadr::fluid
