// SPDX-License-Identifier: MIT
// The error-controlled coupling step: docs/method.md section 1b.
#include "sadr/orchestrator/step_control.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sadr/common/status.hpp"

namespace sadr::orchestrator {

namespace {
/// Standard deviations of the noise that a change must exceed to count (docs/method.md 1b).
constexpr double kNoiseSigmas = 5.0;
double rms(const std::vector<double>& v) {
  double s = 0.0;
  for (const double x : v) s += x * x;
  return v.empty() ? 0.0 : std::sqrt(s / static_cast<double>(v.size()));
}
}  // namespace

std::optional<double> input_error(const InputTrack& track, const InputSample& sample, double h,
                                  const StepTolerance& tol) {
  const std::size_t n = sample.value.size();
  if (n == 0) return 0.0;
  if (!track.has_value || track.value.size() != n) return std::nullopt;
  // The held value minus the value along the step, averaged over the step, per
  // particle: v_i = a (y_i - prev_i) - b increment_i; `noise` bounds sum_i Var(v_i).
  // Second order rules before a second difference exists (the first step): the
  // first-order bound, half the change (a monotone input never strays further).
  double a = 0.5, b = 0.0;
  if (track.rule != HoldRule::kEnd && track.has_increment && track.increment.size() == n) {
    // |y''| from the last three samples, times h^2/12 (trapezoid) or h^2/24 (midpoint).
    const double c = track.rule == HoldRule::kTrapezoid ? 1.0 / 12.0 : 1.0 / 24.0;
    const double s = sample.time - track.time, sp = track.spacing;
    if (!(s > 0.0) || !(sp > 0.0)) return std::nullopt;
    a = c * h * h * 2.0 / (s * (s + sp));
    b = c * h * h * 2.0 / (sp * (s + sp));
  }
  double sum = 0.0, total = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double v =
        a * (sample.value[i] - track.value[i]) - (b != 0.0 ? b * track.increment[i] : 0.0);
    sum += v * v;
    total += v;
  }
  // Sampling noise: its bound, and five standard deviations of the sum of n
  // squared noisy terms about its mean, are not splitting error.
  const double nd = static_cast<double>(n);
  const double noise = a * a * sample.noise + b * b * (b != 0.0 ? track.noise : 0.0);
  const double inflate = 1.0 + kNoiseSigmas * std::sqrt(2.0 / nd);
  const double rms_drift = std::sqrt(std::max(0.0, sum - inflate * noise) / nd);
  // The drift common to all particles, seen through the noise of their mean (variance
  // at most noise / n^2) beyond five of its standard deviations: a drift each
  // particle's noise hides can still bias every mean.
  const double mean_drift =
      std::max(0.0, std::abs(total) / nd - kNoiseSigmas * std::sqrt(noise) / nd);
  const double drift = std::max(rms_drift, mean_drift);
  const double scale = tol.absolute + tol.relative * std::max(rms(track.value), rms(sample.value));
  if (!(scale > 0.0)) return drift > 0.0 ? std::numeric_limits<double>::max() : 0.0;
  return drift / scale;
}

void accept_sample(InputTrack& track, InputSample sample) {
  if (track.has_value && track.value.size() == sample.value.size()) {
    track.increment.resize(sample.value.size());
    for (std::size_t i = 0; i < sample.value.size(); ++i) {
      track.increment[i] = sample.value[i] - track.value[i];
    }
    track.spacing = sample.time - track.time;
    track.noise = sample.noise;
    track.has_increment = true;
  } else {
    track.has_increment = false;
    track.increment.clear();
  }
  track.value = std::move(sample.value);
  track.time = sample.time;
  track.has_value = true;
}

StepController::StepController(const StepTolerance& tol, double first_step, int order)
    : tol_(tol), order_(order), tau_(first_step), min_(first_step * kMinStepFraction) {
  if (!(tol_.max_step >= first_step)) tol_.max_step = first_step;
}

bool StepController::judge(double h, std::optional<double> err) {
  // At the smallest step: a step asked at the minimum may come out longer by the stretch
  // that lands it on an output or end time (up to 1e-9 of it, time_snap) and by rounding; a
  // relative slack of 1e-6 keeps it from being rejected, and redone at the same length, forever.
  const bool at_min = h <= min_ * (1.0 + 1e-6);
  if (err && *err > 1.0 && !at_min) {
    const double fac = kSafety * std::pow(1.0 / *err, 1.0 / order_);
    tau_ = std::max(min_, h * std::max(kFacMin, fac));
    cap_ = tau_;  // grows back by kCapGrowth per accepted step (header)
    ++stats_.rejected;
    return false;
  }
  ++stats_.accepted;
  stats_.smallest = stats_.accepted == 1 ? h : std::min(stats_.smallest, h);
  stats_.largest = std::max(stats_.largest, h);
  if (!err) {
    ++stats_.unestimated;
    return true;  // tau kept
  }
  const double e = *err;
  if (e > 1.0) ++stats_.over_tolerance;
  stats_.largest_error = std::max(stats_.largest_error, e);
  const double fac =
      e > 0.0 ? std::clamp(kSafety * std::pow(1.0 / e, 1.0 / order_), kFacMin, kFacMax) : kFacMax;
  double next = h * fac;
  // A step shortened to land on an output time says the old tau may grow, not shrink.
  if (h < tau_ && fac >= 1.0) next = std::max(next, tau_);
  if (e > 0.0) {
    cap_ = 0.0;  // a measured error: the rejection's memory is superseded
  } else if (cap_ > 0.0) {
    next = std::min(next, cap_);
    cap_ *= kCapGrowth;
    if (cap_ >= tol_.max_step) cap_ = 0.0;
  }
  tau_ = std::clamp(next, min_, tol_.max_step);
  return true;
}

nlohmann::json StepController::state() const {
  return {{"tau", tau_},
          {"cap", cap_},
          {"accepted", stats_.accepted},
          {"rejected", stats_.rejected},
          {"unestimated", stats_.unestimated},
          {"over_tolerance", stats_.over_tolerance},
          {"smallest", stats_.smallest},
          {"largest", stats_.largest},
          {"largest_error", stats_.largest_error}};
}

void StepController::set_state(const nlohmann::json& j) {
  try {
    const double tau = j.at("tau").get<double>();
    if (!(tau >= min_ && tau <= tol_.max_step)) {
      throw InvalidArgument("step control state: tau = " + format_value(tau) + " outside [" +
                            format_value(min_) + ", " + format_value(tol_.max_step) + "]");
    }
    tau_ = tau;
    cap_ = j.at("cap").get<double>();
    stats_.accepted = j.at("accepted").get<std::uint64_t>();
    stats_.rejected = j.at("rejected").get<std::uint64_t>();
    stats_.unestimated = j.at("unestimated").get<std::uint64_t>();
    stats_.over_tolerance = j.at("over_tolerance").get<std::uint64_t>();
    stats_.smallest = j.at("smallest").get<double>();
    stats_.largest = j.at("largest").get<double>();
    stats_.largest_error = j.at("largest_error").get<double>();
  } catch (const nlohmann::json::exception& e) {
    throw InvalidArgument(std::string("step control state: ") + e.what());
  }
}

nlohmann::json tracks_to_json(const std::vector<InputTrack>& tracks) {
  auto out = nlohmann::json::array();
  for (const auto& t : tracks) {
    out.push_back({{"name", t.name},
                   {"has_value", t.has_value},
                   {"time", t.time},
                   {"value", t.value},
                   {"has_increment", t.has_increment},
                   {"spacing", t.spacing},
                   {"noise", t.noise},
                   {"increment", t.increment}});
  }
  return out;
}

void tracks_from_json(const nlohmann::json& j, std::vector<InputTrack>& tracks) {
  try {
    if (!j.is_array() || j.size() != tracks.size()) {
      throw InvalidArgument("step control state: " + std::to_string(tracks.size()) +
                            " coupling inputs expected");
    }
    for (std::size_t k = 0; k < tracks.size(); ++k) {
      const auto& e = j[k];
      InputTrack& t = tracks[k];
      if (e.at("name").get<std::string>() != t.name) {
        throw InvalidArgument("step control state: input " + std::to_string(k) + " is '" +
                              e.at("name").get<std::string>() + "', expected '" + t.name + "'");
      }
      t.has_value = e.at("has_value").get<bool>();
      t.time = e.at("time").get<double>();
      t.value = e.at("value").get<std::vector<double>>();
      t.has_increment = e.at("has_increment").get<bool>();
      t.spacing = e.at("spacing").get<double>();
      t.noise = e.at("noise").get<double>();
      t.increment = e.at("increment").get<std::vector<double>>();
    }
  } catch (const nlohmann::json::exception& e) {
    throw InvalidArgument(std::string("step control state: ") + e.what());
  }
}

}  // namespace sadr::orchestrator
