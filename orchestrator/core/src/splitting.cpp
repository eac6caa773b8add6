// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/splitting.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sadr/common/status.hpp"

namespace sadr::orchestrator {

std::string_view to_string(Operator op) {
  return op == Operator::kFluid ? "fluid" : "ssa";
}

std::vector<Stage> coupling_stages(Splitting splitting, double t, double t_end, bool with_fluid,
                                   bool with_ssa) {
  std::vector<Stage> stages;
  if (with_fluid && with_ssa && splitting == Splitting::kStrang) {
    const double mid = t + 0.5 * (t_end - t);
    stages.push_back({Operator::kFluid, t, mid});
    stages.push_back({Operator::kSsa, t, t_end});
    stages.push_back({Operator::kFluid, mid, t_end});
    return stages;
  }
  if (with_fluid) stages.push_back({Operator::kFluid, t, t_end});
  if (with_ssa) stages.push_back({Operator::kSsa, t, t_end});
  return stages;
}

double time_snap(double t, double tau, double end_time) {
  const double ulp_scale = std::max(std::abs(t), std::abs(end_time));
  return std::max(1e-9 * tau, 64.0 * std::numeric_limits<double>::epsilon() * ulp_scale);
}

std::optional<CouplingStep> next_coupling_step(double t, double tau, double end_time,
                                               std::span<const double> output_times) {
  if (!(tau > 0.0) || !std::isfinite(tau) || !std::isfinite(t)) {
    throw InvalidArgument("next_coupling_step: tau = " + format_value(tau) +
                          ", t = " + format_value(t) + "; need finite t and tau > 0");
  }
  const double snap = time_snap(t, tau, end_time);
  if (t >= end_time - snap) return std::nullopt;
  // First target strictly after t (targets within snap of t count as reached).
  double target = end_time;
  auto it = std::upper_bound(output_times.begin(), output_times.end(), t + snap);
  if (it != output_times.end() && *it < target) target = *it;
  CouplingStep step;
  step.begin = t;
  if (target - (t + tau) <= snap) {
    step.end = target;  // lands: shortened, or stretched over a round-off sliver
  } else {
    step.end = t + tau;
  }
  const bool lands = step.end == target;
  step.last = lands && target == end_time;
  step.output = lands && std::binary_search(output_times.begin(), output_times.end(), target);
  return step;
}

double next_step_length(double t, double tau, double end_time,
                        std::span<const double> output_times) {
  const auto step = next_coupling_step(t, tau, end_time, output_times);
  return step ? step->length() : 0.0;
}

}  // namespace sadr::orchestrator
