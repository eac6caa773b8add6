// SPDX-License-Identifier: MIT
/// \file step_control.hpp
/// The error-controlled coupling step (scene time.tolerance, docs/method.md
/// section 1b): a deterministic estimate of the splitting error of one
/// coupling step from the coupling inputs the two operators hand each other,
/// and the step-size controller that accepts or rejects the step and picks
/// the next one. Plain data, no services: the loop (splitting_loop.cpp) feeds
/// it the inputs' samples; its state goes into the checkpoint.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "sadr/orchestrator/scene.hpp"

namespace sadr::orchestrator {

/// How an operator holds an input over a step [t, t + h] (docs/method.md section 1b).
enum class HoldRule {
  kEnd,        ///< held at one end (Lie): error h/2 |y'| per unit time
  kTrapezoid,  ///< y(t) on the first half, y(t + h) on the second (Strang, fluid reads SSA)
  kMidpoint,   ///< y(t + h/2) over the step (Strang, SSA reads fluid)
};

/// One coupling input: one species, one value per particle, sampled once per accepted step.
struct InputTrack {
  std::string name;
  HoldRule rule = HoldRule::kEnd;
  bool counts = false;  ///< copy numbers: the sampling noise is subtracted
  // The last accepted sample and the increment that led to it.
  bool has_value = false;
  double time = 0.0;
  std::vector<double> value;
  bool has_increment = false;
  double spacing = 0.0;  ///< time between the two samples of `increment`
  double noise = 0.0;    ///< bound on sum_i Var(increment_i) from the sampling noise
  std::vector<double> increment;
};

/// A new sample of one input (same order as the tracks).
struct InputSample {
  double time = 0.0;
  std::vector<double> value;
  double noise = 0.0;  ///< bound on sum_i Var(value_i - previous_i) (0: deterministic)
};

/// RMS over particles of the estimated splitting error of `track` over a
/// step of length h ending in `sample`, divided by absolute + relative * RMS
/// of the input; nullopt when the track has too few samples yet.
std::optional<double> input_error(const InputTrack& track, const InputSample& sample, double h,
                                  const StepTolerance& tol);

/// Makes `sample` the track's last accepted sample.
void accept_sample(InputTrack& track, InputSample sample);

/// What the controller did, over the run (run.json "step_control", the summary).
struct StepControlStats {
  std::uint64_t accepted = 0;
  std::uint64_t rejected = 0;
  std::uint64_t unestimated = 0;     ///< accepted without an estimate (first steps)
  std::uint64_t over_tolerance = 0;  ///< accepted at the smallest step with error > 1
  double smallest = 0.0;             ///< [time]; 0: no step yet
  double largest = 0.0;              ///< [time]
  double largest_error = 0.0;        ///< of the accepted steps, in units of the tolerance
};

class StepController {
 public:
  /// Smallest step: this fraction of the first step (docs/method.md section 1b).
  static constexpr double kMinStepFraction = 1e-3;
  static constexpr double kSafety = 0.9, kFacMin = 0.2, kFacMax = 5.0;
  /// After a rejection, while the estimates read 0 (an error below the sampling noise),
  /// the step is capped at the one the rejection chose and the cap grows by this factor
  /// per accepted step (until max_step or an estimate above 0): otherwise a 0 would grow
  /// the step 5x back into the rejected one, again and again.
  static constexpr double kCapGrowth = 1.25;

  /// @param order 1 (Lie) or 2 (Strang): the error per unit time is O(tau^order)
  StepController(const StepTolerance& tol, double first_step, int order);

  /// The step to try next (before landing on output and end times) [time].
  [[nodiscard]] double tau() const { return tau_; }
  [[nodiscard]] double min_step() const { return min_; }
  [[nodiscard]] const StepTolerance& tolerance() const { return tol_; }
  [[nodiscard]] int order() const { return order_; }
  [[nodiscard]] const StepControlStats& stats() const { return stats_; }

  /// Judges a step of length h with estimated error `err` (in units of the
  /// tolerance; nullopt: no estimate yet, accepted, tau kept) and sets the next tau.
  /// @return true: accepted
  bool judge(double h, std::optional<double> err);

  /// The controller's state (tau and counters), exactly (doubles round-trip).
  [[nodiscard]] nlohmann::json state() const;
  /// @throws sadr::InvalidArgument on a malformed state
  void set_state(const nlohmann::json& j);

 private:
  StepTolerance tol_;
  int order_ = 1;
  double tau_ = 0.0, min_ = 0.0;
  double cap_ = 0.0;  ///< largest next step after a rejection (0: none)
  StepControlStats stats_;
};

/// The tracks as JSON and back (checkpoint), exactly.
nlohmann::json tracks_to_json(const std::vector<InputTrack>& tracks);
void tracks_from_json(const nlohmann::json& j, std::vector<InputTrack>& tracks);

}  // namespace sadr::orchestrator
