// SPDX-License-Identifier: MIT
/// \file splitting.hpp
/// The operator-splitting schedule as plain data, and the choice of the next
/// coupling step so that steps land exactly on output times and on the end.
///
/// Lie (first order):     fluid [t, t+dt]   -> ssa [t, t+dt]
/// Strang (second order): fluid [t, t+dt/2] -> ssa [t, t+dt] -> fluid [t+dt/2, t+dt]
/// Each operator advances its own state over the interval given; the SSA is
/// told the absolute end time, the fluid the interval length.
#pragma once

#include <limits>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "sadr/orchestrator/scene.hpp"

namespace sadr::orchestrator {

enum class Operator { kFluid, kSsa };
std::string_view to_string(Operator op);

/// One operator application over [begin, end] (absolute times) [time].
struct Stage {
  Operator op = Operator::kFluid;
  double begin = 0.0;
  double end = 0.0;
  [[nodiscard]] double length() const { return end - begin; }
  bool operator==(const Stage&) const = default;
};

/// The stages of one coupling step [t, t_end] in execution order.
/// Operators that the plan skips are left out (`with_fluid`, `with_ssa`);
/// with one operator left, Strang reduces to a single stage over [t, t_end].
/// @param t start of the step [time]
/// @param t_end end of the step, > t [time]
std::vector<Stage> coupling_stages(Splitting splitting, double t, double t_end,
                                   bool with_fluid = true, bool with_ssa = true);

/// One coupling step chosen by next_coupling_step().
struct CouplingStep {
  double begin = 0.0;   ///< t [time]
  double end = 0.0;     ///< exact end time: an output time or end time when it lands on one
  bool output = false;  ///< `end` is one of the output times: write a frame after the step
  bool last = false;    ///< `end` is the end time
  [[nodiscard]] double length() const { return end - begin; }
};

/// Times closer than this to each other are the same instant: 1e-9 tau, but
/// never below 64 ulp of the larger of |t| and |end_time| [time].
double time_snap(double t, double tau, double end_time);

/// The next coupling step from t: normally tau long, but shortened to land
/// exactly on the next output time or the end time, and stretched (by at most
/// time_snap()) instead of leaving a sliver shorter than time_snap() before
/// it, so no zero-length or round-off-length step is ever produced. The end
/// of a landing step is the target value itself (not t + dt), so time does
/// not drift however many steps are taken.
/// @param t current time [time]
/// @param tau coupling step, > 0 [time]
/// @param end_time end of the run [time]
/// @param output_times sorted output times (may include times <= t)
/// @return nullopt when t has reached end_time (within time_snap())
std::optional<CouplingStep> next_coupling_step(double t, double tau, double end_time,
                                               std::span<const double> output_times);

/// A schedule that skips the coupling step (Plan::frame_to_frame: nothing
/// moves and nothing is reset between SSA calls, so the length of an SSA call
/// does not matter): besides the output times and the end, steps also end on
/// every multiple of `checkpoint_every` (when > 0) and on `stop_at`.
struct FrameToFrame {
  double checkpoint_every = 0.0;                             ///< [time]; 0 = none
  double stop_at = std::numeric_limits<double>::infinity();  ///< [time]
};

/// At most this many coupling steps tau per frame-to-frame step: one SSA call
/// must answer within the client's timeout (--timeout, 120 s), and a run to a
/// single output time far away would otherwise be one call.
inline constexpr double kFrameToFrameMaxSteps = 100.0;

/// next_coupling_step() of a frame-to-frame schedule: one step from t to the
/// first of the next output time, end time, checkpoint time, stop time and
/// t + kFrameToFrameMaxSteps tau; otherwise `tau` only sets time_snap().
/// Targets within time_snap() of each other are one target (the output or end
/// time wins).
/// @param frame_to_frame nullptr: the same as next_coupling_step(t, tau, end_time, output_times)
std::optional<CouplingStep> next_coupling_step(double t, double tau, double end_time,
                                               std::span<const double> output_times,
                                               const FrameToFrame* frame_to_frame);

/// next_coupling_step() of the error-controlled step (time.tolerance): when the next
/// output or end time is more than tau but less than 2 tau ahead, a step of half the
/// distance, so that the landing step is not a sliver (tau is the controller's largest
/// safe step; the two halves are both shorter).
std::optional<CouplingStep> next_controlled_step(double t, double tau, double end_time,
                                                 std::span<const double> output_times);

/// Length of next_coupling_step(); 0 when the run is finished [time].
double next_step_length(double t, double tau, double end_time,
                        std::span<const double> output_times);

}  // namespace sadr::orchestrator
