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

namespace {
void check_step_inputs(double t, double tau) {
  if (!(tau > 0.0) || !std::isfinite(tau) || !std::isfinite(t)) {
    throw InvalidArgument("next_coupling_step: tau = " + format_value(tau) +
                          ", t = " + format_value(t) + "; need finite t and tau > 0");
  }
}

/// The first output time strictly after t + snap, or the end time.
double next_target(double t, double snap, double end_time, std::span<const double> output_times) {
  double target = end_time;
  auto it = std::upper_bound(output_times.begin(), output_times.end(), t + snap);
  if (it != output_times.end() && *it < target) target = *it;
  return target;
}

CouplingStep landing_step(double t, double end, double end_time,
                          std::span<const double> output_times) {
  CouplingStep step;
  step.begin = t;
  step.end = end;
  step.last = end == end_time;
  step.output = std::binary_search(output_times.begin(), output_times.end(), end);
  return step;
}
}  // namespace

std::optional<CouplingStep> next_coupling_step(double t, double tau, double end_time,
                                               std::span<const double> output_times) {
  check_step_inputs(t, tau);
  const double snap = time_snap(t, tau, end_time);
  if (t >= end_time - snap) return std::nullopt;
  // First target strictly after t (targets within snap of t count as reached).
  const double target = next_target(t, snap, end_time, output_times);
  // Lands (shortened, or stretched over a round-off sliver), or a plain step.
  if (target - (t + tau) <= snap) return landing_step(t, target, end_time, output_times);
  return CouplingStep{t, t + tau, false, false};
}

std::optional<CouplingStep> next_coupling_step(double t, double tau, double end_time,
                                               std::span<const double> output_times,
                                               const FrameToFrame* frame_to_frame) {
  if (!frame_to_frame) return next_coupling_step(t, tau, end_time, output_times);
  check_step_inputs(t, tau);
  const double snap = time_snap(t, tau, end_time);
  if (t >= end_time - snap) return std::nullopt;
  const double target = next_target(t, snap, end_time, output_times);
  double end = target;
  // A checkpoint or stop time counts when it is after t and clearly before the
  // target (within snap of the target, the target itself serves).
  auto earlier = [&](double c) {
    if (c > t + snap && c < target - snap && c < end) end = c;
  };
  if (const double every = frame_to_frame->checkpoint_every; every > 0.0) {
    earlier((std::floor((t + snap) / every) + 1.0) * every);
  }
  earlier(frame_to_frame->stop_at);
  earlier(t + kFrameToFrameMaxSteps * tau);
  return landing_step(t, end, end_time, output_times);
}

std::optional<CouplingStep> next_controlled_step(double t, double tau, double end_time,
                                                 std::span<const double> output_times) {
  auto cs = next_coupling_step(t, tau, end_time, output_times);
  if (!cs || cs->output || cs->last) return cs;
  const auto two = next_coupling_step(t, 2.0 * tau, end_time, output_times);
  if (two && (two->output || two->last)) {
    return next_coupling_step(t, 0.5 * two->length(), end_time, output_times);
  }
  return cs;
}

double next_step_length(double t, double tau, double end_time,
                        std::span<const double> output_times) {
  const auto step = next_coupling_step(t, tau, end_time, output_times);
  return step ? step->length() : 0.0;
}

}  // namespace sadr::orchestrator
