// SPDX-License-Identifier: MIT
// The coupling loop's error-controlled step (scene time.tolerance,
// docs/method.md section 1b): snapshot both services, try the step, estimate
// its splitting error from the coupling inputs, accept it or restore and try
// a shorter one.
#include <algorithm>

#include "sadr/common/log.hpp"
#include "sadr/common/status.hpp"
#include "sadr/orchestrator/scoped_timer.hpp"
#include "sadr/orchestrator/splitting_loop.hpp"

namespace sadr::orchestrator {

namespace {
std::vector<double> as_doubles(const std::vector<std::int64_t>& v) {
  return {v.begin(), v.end()};
}
const std::vector<std::int64_t>& counts_of(const SpeciesCounts& c, const std::string& name) {
  const auto it = std::find(c.names.begin(), c.names.end(), name);
  if (it == c.names.end() || c.values.size() != c.names.size()) {
    throw Error(StatusCode::kInternal, "step control: no copy numbers of '" + name + "'");
  }
  return c.values[static_cast<std::size_t>(it - c.names.begin())];
}
const std::vector<double>& values_of(const SpeciesConcentrations& c, const std::string& name) {
  for (const auto& [n, v] : c) {
    if (n == name) return v;
  }
  throw Error(StatusCode::kInternal, "step control: no concentrations of '" + name + "'");
}
}  // namespace

/// The inputs at the start of the run (t_): the copy numbers and the frozen concentrations.
std::vector<InputSample> SplittingLoop::start_samples() {
  std::vector<InputSample> out(tracks_.size());
  const bool need_frozen =
      std::any_of(tracks_.begin(), tracks_.end(), [](const InputTrack& t) { return !t.counts; });
  const SpeciesConcentrations frozen =
      need_frozen ? fluid_->frame(s_.frozen).concentrations : SpeciesConcentrations{};
  const SpeciesCounts counts = s_.back_transfer.empty() ? SpeciesCounts{} : back_transfer_counts();
  for (std::size_t k = 0; k < tracks_.size(); ++k) {
    out[k].time = t_;
    if (tracks_[k].counts) {
      out[k].value = as_doubles(counts_of(counts, tracks_[k].name));
    } else if (need_frozen) {
      out[k].value = values_of(frozen, tracks_[k].name);
    }
  }
  return out;
}

/// The inputs after the step just tried: the copy numbers after its SSA stage
/// (noise bound from its events) and the concentrations that stage read.
std::vector<InputSample> SplittingLoop::end_samples(const CouplingStep& cs, std::uint64_t events) {
  std::vector<InputSample> out(tracks_.size());
  const SpeciesCounts counts = s_.back_transfer.empty() ? SpeciesCounts{} : back_transfer_counts();
  for (std::size_t k = 0; k < tracks_.size(); ++k) {
    const InputTrack& t = tracks_[k];
    if (t.counts) {
      out[k].time = cs.end;
      out[k].value = as_doubles(counts_of(counts, t.name));
      // Each event (or leaped molecule) changes the copy numbers of at most two particles
      // by at most sqrt(jump2) each: sum_i Var(change_i) <= 2 jump2 E[events].
      out[k].noise = 2.0 * s_.jump2 * static_cast<double>(events);
    } else {
      out[k].time = t.rule == HoldRule::kMidpoint ? cs.begin + 0.5 * cs.length() : cs.end;
      out[k].value = values_of(last_frozen_, t.name);
    }
  }
  return out;
}

CouplingStep SplittingLoop::controlled_step(CouplingStep cs) {
  const StepTolerance& tol = control_->tolerance();
  if (std::any_of(tracks_.begin(), tracks_.end(),
                  [](const InputTrack& t) { return !t.has_value; })) {
    auto start = start_samples();
    for (std::size_t k = 0; k < tracks_.size(); ++k) {
      if (!start[k].value.empty()) accept_sample(tracks_[k], std::move(start[k]));
    }
  }
  for (;;) {
    const double t0 = t_;
    const std::uint64_t step0 = step_;
    const SpeciesCounts counts0 = counts_;
    const bool had_counts = has_counts_;
    std::string fluid_snap, ssa_snap;
    {
      ScopedTimer timer(stats_.timings_s, "step_control_snapshot");
      fluid_snap = fluid_->snapshot(step_);
      ssa_snap = ssa_->snapshot(step_);
    }
    // Leaped molecules move like diffusion events: both enter the noise bound.
    const std::uint64_t moves0 = stats_.ssa_events + stats_.ssa_leaped_molecules;
    step(cs, false);
    auto samples = end_samples(cs, stats_.ssa_events + stats_.ssa_leaped_molecules - moves0);
    // The largest error over the inputs that have an estimate; none: nothing to estimate yet.
    std::optional<double> err;
    if (tracks_.empty()) err = 0.0;  // nothing crosses: no splitting error
    for (std::size_t k = 0; k < tracks_.size(); ++k) {
      if (const auto e = input_error(tracks_[k], samples[k], cs.length(), tol)) {
        err = std::max(err.value_or(0.0), *e);
      }
    }
    if (control_->judge(cs.length(), err)) {
      for (std::size_t k = 0; k < tracks_.size(); ++k)
        accept_sample(tracks_[k], std::move(samples[k]));
      const auto& st = control_->stats();
      stats_.step_control = {
          {"accepted", st.accepted},           {"rejected", st.rejected},
          {"unestimated", st.unestimated},     {"over_tolerance", st.over_tolerance},
          {"smallest_step", st.smallest},      {"largest_step", st.largest},
          {"largest_error", st.largest_error}, {"next_step", control_->tau()}};
      return cs;
    }
    log::debug("coupling step [", cs.begin, ", ", cs.end, "] rejected: error ", err.value_or(0.0),
               " of the tolerance; next try ", control_->tau());
    {
      ScopedTimer timer(stats_.timings_s, "step_control_restore");
      fluid_->restore(fluid_snap);
      ssa_->restore(ssa_snap);
    }
    t_ = t0;
    step_ = step0;
    counts_ = counts0;
    has_counts_ = had_counts;
    stage_forces_.clear();
    last_frozen_.clear();
    const auto next = next_controlled_step(t_, control_->tau(), s_.t_end, s_.output_times);
    if (!next) throw Error(StatusCode::kInternal, "step control: no step left after a rejection");
    cs = *next;
  }
}

std::string SplittingLoop::control_state() const {
  if (!control_) return {};
  return nlohmann::json{{"controller", control_->state()}, {"inputs", tracks_to_json(tracks_)}}
      .dump();
}

void SplittingLoop::restore_control_state(const std::string& bytes) {
  if (!control_) return;
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(bytes);
  } catch (const nlohmann::json::exception& e) {
    throw InvalidArgument(std::string("step control state: ") + e.what());
  }
  if (!j.is_object() || !j.contains("controller") || !j.contains("inputs")) {
    throw InvalidArgument("step control state: needs 'controller' and 'inputs'");
  }
  control_->set_state(j["controller"]);
  tracks_from_json(j["inputs"], tracks_);
}

}  // namespace sadr::orchestrator
