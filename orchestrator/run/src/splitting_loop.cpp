// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/splitting_loop.hpp"

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <utility>

#include "sadr/common/log.hpp"
#include "sadr/common/status.hpp"
#include "sadr/orchestrator/scoped_timer.hpp"

namespace sadr::orchestrator {

LoopSettings make_loop_settings(const Scene& scene, const Plan& plan) {
  LoopSettings s;
  s.splitting = scene.time.splitting;
  s.tau = scene.time.coupling_step;
  s.t_end = scene.time.end;
  s.output_times = scene.output.times;
  s.checkpoint_every = scene.output.checkpoint_every;
  s.fluid_stepping = plan.fluid_stepping;
  s.fluid_calls_per_step = plan.fluid_calls_per_step;
  s.geometry_each_step = plan.particles_to_ssa_each_step;
  if (plan.back_transfer) s.back_transfer = plan.back_transfer_species;
  s.frozen = plan.frozen_species;
  s.overlap = plan.overlap && plan.overlap_allowed;
  s.frame_to_frame = plan.frame_to_frame;
  if (plan.step_control) {
    s.tolerance = scene.time.tolerance;
    for (const auto& rx : scene.reactions) {
      for (const auto& sp : plan.back_transfer_species) {
        double change = 0.0;
        for (const auto& e : rx.products) change += e.species == sp ? e.count : 0.0;
        for (const auto& e : rx.reactants) change -= e.species == sp ? e.count : 0.0;
        s.jump2 = std::max(s.jump2, change * change);
      }
    }
  }
  return s;
}

/// One job at a time on a persistent thread: the SSA stage of the overlapped
/// loop. The job owns the SSA client while it runs; the mutex hand-over orders
/// every use of the client (and its ZeroMQ socket) between the two threads.
class SplittingLoop::Worker {
 public:
  Worker() : thread_([this] { loop(); }) {}
  ~Worker() {
    {
      std::lock_guard lock(mutex_);
      quit_ = true;
    }
    cv_.notify_all();
    thread_.join();  // a running job ends by itself (every service call has a timeout)
  }
  Worker(const Worker&) = delete;
  Worker& operator=(const Worker&) = delete;

  /// Starts `job`; the previous one must have been waited for.
  void submit(std::function<void()> job) {
    {
      std::lock_guard lock(mutex_);
      job_ = std::move(job);
      busy_ = true;
      error_ = nullptr;
    }
    cv_.notify_all();
  }
  /// Blocks until the job has finished; rethrows its exception.
  void wait() {
    std::unique_lock lock(mutex_);
    cv_.wait(lock, [&] { return !busy_; });
    if (auto e = std::exchange(error_, nullptr)) std::rethrow_exception(e);
  }

 private:
  void loop() {
    std::unique_lock lock(mutex_);
    for (;;) {
      cv_.wait(lock, [&] { return quit_ || job_; });
      if (!job_) return;  // quit with nothing to do
      auto job = std::exchange(job_, nullptr);
      lock.unlock();
      std::exception_ptr error;
      try {
        job();
      } catch (...) {
        error = std::current_exception();
      }
      lock.lock();
      error_ = error;
      busy_ = false;
      cv_.notify_all();
    }
  }

  std::mutex mutex_;
  std::condition_variable cv_;
  std::function<void()> job_;
  bool busy_ = false;
  bool quit_ = false;
  std::exception_ptr error_;
  std::thread thread_;  // last: started after the members it uses
};

/// An SSA stage: its request, then what the call reported (filled by run_ssa,
/// on the worker when overlapped; read by the main thread after it).
struct SplittingLoop::SsaJob {
  std::uint64_t step_index = 0;
  double t_end = 0.0;
  Geometry geometry;             ///< empty: the graph is kept
  SpeciesConcentrations frozen;  ///< hybrid reactions' deterministic inputs (LoopSettings::frozen)
  double call_seconds = 0.0;
  SsaStep result;
};

SplittingLoop::SplittingLoop(FluidService* fluid, SsaService* ssa, LoopSettings settings,
                             RunManifest& stats)
    : fluid_(fluid), ssa_(ssa), s_(std::move(settings)), stats_(stats) {
  if (!fluid_) s_.fluid_stepping = false;
  if (!ssa_) s_.back_transfer.clear();
  // Results are identical only when the fluid never reads the SSA.
  overlap_ = s_.overlap && fluid_ && ssa_ && s_.fluid_stepping && s_.back_transfer.empty() &&
             s_.splitting == Splitting::kLie && !s_.tolerance;
  if (s_.tolerance && fluid_ && ssa_ && s_.fluid_stepping) {
    const bool strang = s_.splitting == Splitting::kStrang;
    control_ = std::make_unique<StepController>(*s_.tolerance, s_.tau, strang ? 2 : 1);
    auto track = [&](const std::string& name, HoldRule rule, bool counts) {
      InputTrack t;
      t.name = name;
      t.rule = rule;
      t.counts = counts;
      tracks_.push_back(std::move(t));
    };
    for (const auto& name : s_.back_transfer) {
      track(name, strang ? HoldRule::kTrapezoid : HoldRule::kEnd, true);
    }
    for (const auto& name : s_.frozen)
      track(name, strang ? HoldRule::kMidpoint : HoldRule::kEnd, false);
  }
}

SplittingLoop::~SplittingLoop() = default;

void SplittingLoop::resume_at(double t, std::uint64_t steps) {
  t_ = t;
  step_ = steps;
  has_counts_ = false;  // the restored SSA state is asked again
}

bool SplittingLoop::run(const LoopHooks& hooks) {
  const auto& outputs = s_.output_times;
  const double tau = s_.tau, t_end = s_.t_end;
  double next_checkpoint = next_checkpoint_after(t_);
  double last_checkpoint_time = -1.0;
  auto stop_requested = [&] { return hooks.stop_requested && hooks.stop_requested(); };
  auto reaches_stop_at = [&](double t) { return t >= s_.stop_at - time_snap(t, tau, t_end); };
  // Nothing moves (frame_to_frame): one step per output/checkpoint/stop time.
  const FrameToFrame landings{s_.checkpoint_every, s_.stop_at};
  const FrameToFrame* ftf = s_.frame_to_frame ? &landings : nullptr;
  auto next_step = [&] {
    return control_ ? next_controlled_step(t_, control_->tau(), t_end, outputs)
                    : next_coupling_step(t_, tau, t_end, outputs, ftf);
  };
  if (overlap_ && !worker_) worker_ = std::make_unique<Worker>();
  bool interrupted = false;
  const auto loop_t0 = Clock::now();
  try {
    while (auto cs = next_step()) {
      // Overlap: leave the SSA stage of this step running while the fluid
      // computes the next one, unless the step ends where both services are
      // needed at once (a frame, a checkpoint, the stop time, the end) or a
      // stop was requested. The same stages, in the same order per service.
      const bool defer_ssa = overlap_ && !cs->output && !cs->last && cs->end < next_checkpoint &&
                             !reaches_stop_at(cs->end) && !stop_requested() &&
                             next_coupling_step(cs->end, tau, t_end, outputs, ftf);
      if (control_) {
        *cs = controlled_step(*cs);
      } else {
        step(*cs, defer_ssa);
      }
      for (const auto& sf : stage_forces_) {
        if (hooks.body_forces) hooks.body_forces(sf.t, sf.dt, sf.forces);
      }
      stage_forces_.clear();
      if (cs->output) {
        drain();  // both services at the same time
        const auto it = std::lower_bound(outputs.begin(), outputs.end(), cs->end);
        if (hooks.frame) hooks.frame(static_cast<std::size_t>(it - outputs.begin()), cs->end);
      }
      const bool stop = stop_requested() || reaches_stop_at(t_);
      if (stop || t_ >= next_checkpoint) {
        drain();
        if (hooks.checkpoint) hooks.checkpoint();
        last_checkpoint_time = t_;
        next_checkpoint = next_checkpoint_after(t_);
      }
      if (hooks.progress) hooks.progress(t_, step_);
      if (stop) {
        interrupted = true;
        break;
      }
    }
    drain();
  } catch (...) {
    drain_after_failure();
    throw;
  }
  stats_.timings_s["coupling_loop"] +=
      std::chrono::duration<double>(Clock::now() - loop_t0).count();
  if (!interrupted && s_.checkpoint_every > 0 && last_checkpoint_time != t_ && hooks.checkpoint) {
    hooks.checkpoint();
  }
  return interrupted;
}

/// One coupling step. With `defer_ssa` (Lie, overlap on) the SSA stage is
/// left running on the worker thread; the next call to step() (or drain())
/// waits for it after its fluid stage.
void SplittingLoop::step(const CouplingStep& cs, bool defer_ssa) {
  const auto stages = coupling_stages(s_.splitting, cs.begin, cs.end, s_.fluid_stepping, !!ssa_);
  const std::uint64_t calls = static_cast<std::uint64_t>(std::max(1, s_.fluid_calls_per_step));
  std::uint64_t fluid_call = 0;
  bool moved = false;
  // The geometry the fluid stage just before an SSA stage returned (one round
  // trip: no separate geometry read).
  Geometry geometry;
  SpeciesConcentrations frozen;  // the same fluid stage's concentrations (hybrid reactions)
  static const std::vector<std::string> kNone;
  for (std::size_t k = 0; k < stages.size(); ++k) {
    const Stage& stage = stages[k];
    if (stage.op == Operator::kFluid) {
      const SpeciesCounts counts =
          s_.back_transfer.empty() ? SpeciesCounts{} : back_transfer_counts();
      ScopedTimer timer(stats_.timings_s, "fluid");
      const bool want_geometry = ssa_ && s_.geometry_each_step && k + 1 < stages.size() &&
                                 stages[k + 1].op != Operator::kFluid;
      const bool before_ssa = ssa_ && k + 1 < stages.size() && stages[k + 1].op != Operator::kFluid;
      FluidStep rep = fluid_->advance(step_ * calls + fluid_call++, stage.length(), want_geometry,
                                      counts, before_ssa ? s_.frozen : kNone);
      stats_.timings_s["fluid_compute"] += rep.compute_seconds;
      stats_.fluid_substeps += rep.substeps;
      stats_.note_fluid_limit(rep.stable_time_step, rep.limiting_criterion, rep.time);
      moved = rep.particles_moved || moved;
      geometry = std::move(rep.geometry);
      if (before_ssa) frozen = std::move(rep.concentrations);
      if (!rep.body_forces.empty()) {
        stage_forces_.push_back({stage.end, stage.length(), std::move(rep.body_forces)});
      }
    } else {
      // The SSA stage of the previous step (overlapped with the fluid stage
      // just done) comes first: exposed time, the SSA not hidden by the fluid.
      drain();
      ScopedTimer exposed(stats_.timings_s, "ssa_wait");
      auto job = std::make_unique<SsaJob>();
      job->step_index = step_;
      job->t_end = stage.end;
      if (moved && s_.geometry_each_step) {
        ScopedTimer timer(stats_.timings_s, "transfer");
        job->geometry = geometry.empty() ? fluid_->geometry() : std::move(geometry);
        moved = false;
      }
      geometry = Geometry{};
      if (!s_.frozen.empty() && frozen.size() != s_.frozen.size()) {
        throw Error(StatusCode::kInternal,
                    "coupling step " + std::to_string(step_) +
                        ": the SSA stage needs the frozen concentrations of the hybrid "
                        "reactions, but no fluid stage returned them just before it");
      }
      if (control_) last_frozen_ = frozen;
      job->frozen = std::move(frozen);
      frozen = {};
      if (defer_ssa && k + 1 == stages.size()) {
        pending_ = std::move(job);
        worker_->submit([this, j = pending_.get()] { run_ssa(*j); });
        ++stats_.overlapped_steps;
      } else {
        run_ssa(*job);
        finish_ssa(*job);
      }
    }
  }
  t_ = cs.end;
  ++step_;
}

SpeciesCounts SplittingLoop::back_transfer_counts() {
  ScopedTimer timer(stats_.timings_s, "back_transfer");
  if (!has_counts_) {  // none since Init or a restore: ask
    counts_ = ssa_->counts(s_.back_transfer);
    has_counts_ = true;
  }
  return counts_;
}

/// The SSA call of one stage (main thread, or the worker when overlapped:
/// touches only ssa_ and the job).
void SplittingLoop::run_ssa(SsaJob& job) {
  const auto t0 = Clock::now();
  job.result = ssa_->advance(job.step_index, job.t_end, std::move(job.geometry), s_.back_transfer,
                             job.frozen);
  job.call_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
}

void SplittingLoop::finish_ssa(const SsaJob& job) {
  stats_.timings_s["ssa"] += job.call_seconds;
  stats_.timings_s["ssa_graph"] += job.result.graph_seconds;
  stats_.timings_s["ssa_nsm"] += job.result.nsm_seconds;
  stats_.ssa_events += job.result.events;
  stats_.ssa_leaped_molecules += job.result.leaped_molecules;
  if (!s_.back_transfer.empty()) {
    counts_ = job.result.counts;
    has_counts_ = true;
  }
}

/// Waits for the SSA stage left running by step() (if any); rethrows its error.
void SplittingLoop::drain() {
  if (!pending_) return;
  ScopedTimer exposed(stats_.timings_s, "ssa_wait");
  const auto job = std::move(pending_);
  worker_->wait();
  finish_ssa(*job);
}

/// After a failure on the main thread: joins the SSA stage in flight (its own
/// error, if any, is logged; the main thread's error is the one reported).
void SplittingLoop::drain_after_failure() noexcept {
  if (!pending_) return;
  try {
    worker_->wait();
  } catch (const std::exception& e) {
    log::warn("the overlapped ssa_service call failed too: ", e.what());
  } catch (...) {
  }
  pending_.reset();
}

double SplittingLoop::next_checkpoint_after(double t) const {
  const double every = s_.checkpoint_every;
  if (!(every > 0)) return std::numeric_limits<double>::infinity();
  const double snap = time_snap(t, s_.tau, s_.t_end);
  return (std::floor((t + snap) / every) + 1) * every - snap;
}

}  // namespace sadr::orchestrator
