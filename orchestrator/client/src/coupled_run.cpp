// SPDX-License-Identifier: MIT
// One realization: the services' clients, the splitting loop, frames and
// checkpoints put together, and the run manifest.
#include "sadr/orchestrator/coupled_run.hpp"

#include <cmath>
#include <optional>

#include "sadr/common/log.hpp"
#include "sadr/orchestrator/body_force_log.hpp"
#include "sadr/orchestrator/checkpointing.hpp"
#include "sadr/orchestrator/flow_replay.hpp"
#include "sadr/orchestrator/frame_output.hpp"
#include "sadr/orchestrator/progress.hpp"
#include "sadr/orchestrator/run_manifest.hpp"
#include "sadr/orchestrator/scene_messages.hpp"
#include "sadr/orchestrator/scoped_timer.hpp"
#include "sadr/orchestrator/seeds.hpp"
#include "sadr/orchestrator/service_clients.hpp"
#include "sadr/orchestrator/splitting_loop.hpp"

namespace sadr::orchestrator {
namespace {

class CoupledRun {
 public:
  CoupledRun(const Scene& scene, const Plan& plan, const ServiceEndpoints& endpoints,
             const RunOptions& options)
      : scene_(scene),
        plan_(plan),
        options_(options),
        seed_(realization_seed(scene.seed, options.realization)) {
    const std::string run_id = scene_.source_hash + "/" + std::to_string(seed_);
    if (!options.flow_replay.empty()) {
      replay_.emplace(options.flow_replay, fluid_key(scene_, plan_));
    } else if (plan_.fluid_service) {
      if (endpoints.fluid.empty()) throw FailedPrecondition("the plan needs fluid_service");
      fluid_.emplace(endpoints.fluid, options.timeout);
      if (options.liveness) fluid_->set_liveness_check(options.liveness);
      fluid_->set_run_id(run_id);
    }
    if (plan_.ssa_service) {
      if (endpoints.ssa.empty()) throw FailedPrecondition("the plan needs ssa_service");
      ssa_.emplace(endpoints.ssa, options.timeout);
      if (options.liveness) ssa_->set_liveness_check(options.liveness);
      ssa_->set_run_id(run_id);
    }
    if (options.shared_geometry && fluid_ && ssa_ && plan_.particles_to_ssa_each_step) {
      geometry_ = GeometryChannel::on_this_host(scene_.particles.size());
    }
    if (fluid_) fluid_->use_geometry_channel(&geometry_);
    if (ssa_) ssa_->use_geometry_channel(&geometry_);
    manifest_.scene_path = scene_.source_path.string();
    manifest_.scene_hash = scene_.source_hash;
    manifest_.overrides = scene_.overrides;
    manifest_.scene_seed = scene_.seed;
    manifest_.realization = options.realization;
    manifest_.seed = seed_;
    manifest_.mode = options.mode;
    manifest_.started_utc = utc_now_iso8601();
    manifest_.plan = plan_.to_json();
    frames_.emplace(scene_, options.output_dir, manifest_);
    loop_.emplace(fluid(), ssa(), loop_settings(), manifest_);
  }

  RunResult execute() {
    init_services();
    RunResult result;
    if (options_.resume) {
      restore(*options_.resume);
    } else if (!scene_.output.times.empty() &&
               std::abs(scene_.output.times.front()) <=
                   time_snap(0.0, scene_.time.coupling_step, scene_.time.end)) {
      write_frame(0, 0.0);
      ++result.frames;
    }
    Progress progress(loop_->time(), scene_.time.end, options_.progress_label, options_.progress);
    LoopHooks hooks;
    hooks.frame = [&](std::size_t index, double t) {
      write_frame(index, t);
      ++result.frames;
    };
    hooks.checkpoint = [&] { result.last_checkpoint = checkpoint(); };
    hooks.stop_requested = [&] { return options_.interrupt && options_.interrupt->load(); };
    hooks.progress = [&](double t, std::uint64_t steps) { progress.update(t, steps); };
    if (!scene_.fluid.body_forces.empty()) {  // body_forces.csv beside the frames
      forces_.emplace(options_.output_dir, scene_.time.end, options_.resume ? loop_->time() : -1.0);
      hooks.body_forces = [&](double t, double dt, const std::vector<BodyForceSample>& f) {
        forces_->add(t, dt, f);
        manifest_.body_forces = forces_->summary();
      };
    }
    result.interrupted = loop_->run(hooks);
    progress.finish(loop_->time(), loop_->steps());
    manifest_.status = result.interrupted ? "interrupted" : "ok";
    manifest_.finished_utc = utc_now_iso8601();
    write_manifest();
    result.steps = loop_->steps();
    result.time = loop_->time();
    return result;
  }

  void fail(const std::string& why) {
    manifest_.status = "failed: " + why;
    manifest_.finished_utc = utc_now_iso8601();
    try {
      write_manifest();
    } catch (...) {
    }
  }

 private:
  LoopSettings loop_settings() const {
    LoopSettings s = make_loop_settings(scene_, plan_);
    s.stop_at = options_.stop_at;
    return s;
  }
  FluidService* fluid() {
    if (replay_) return &*replay_;
    return fluid_ ? &*fluid_ : nullptr;
  }
  SsaService* ssa() { return ssa_ ? &*ssa_ : nullptr; }

  void init_services() {
    ScopedTimer timer(manifest_.timings_s, "init");
    if (fluid_) {
      const FluidSubsteps f = fluid_substeps(fluid_->init(make_fluid_init(scene_, plan_, seed_)));
      if (f.known()) {  // the backend's sub-steps ahead at t = 0 (the plan printed the same)
        manifest_.fluid_at_t0 = {{"stable_time_step", f.stable_time_step},
                                 {"limiting_criterion", f.limiting_criterion},
                                 {"max_substep", f.max_substep},
                                 {"substep_criterion", f.criterion()}};
      }
    }
    if (ssa_) ssa_->init(make_ssa_init(scene_, plan_, seed_, scene_.particles));
  }

  void restore(const LoadedCheckpoint& cp) {
    ScopedTimer timer(manifest_.timings_s, "restore");
    const auto blob = cp.blobs.find("fluid");
    if (fluid_ && blob != cp.blobs.end() && is_flow_replay_snapshot(blob->second.bytes)) {
      throw InvalidArgument(
          "this checkpoint is of a realization that replays the flow of its ensemble "
          "(flow_replay.bin in the ensemble's folder): resume the ensemble, sadr resume DIR");
    }
    restore_checkpoint(cp, fluid(), ssa());
    if (loop_->controller()) {  // time.tolerance: the controller's tau, counters and inputs
      const auto it = cp.blobs.find("step_control");
      if (it == cp.blobs.end()) throw InvalidArgument("checkpoint has no 'step_control' blob");
      loop_->restore_control_state(it->second.bytes);
    }
    loop_->resume_at(cp.manifest.time, cp.manifest.step_index);
    frames_->relist_until(loop_->time());
    log::info("resumed at t = ", loop_->time(), " after ", loop_->steps(), " coupling steps");
  }

  void write_frame(std::size_t index, double t) {
    std::vector<SpeciesColumn> columns;
    {
      ScopedTimer timer(manifest_.timings_s, "output");
      columns = frames_->write(index, t, fluid(), ssa(), scene_.particles);
      if (options_.on_frame) options_.on_frame(index, t, columns);
      write_manifest();
    }
  }

  std::filesystem::path checkpoint() {
    ScopedTimer timer(manifest_.timings_s, "checkpoint");
    const CheckpointPoint at{seed_, options_.realization, loop_->steps(), loop_->time()};
    return save_checkpoint(scene_, at, fluid(), ssa(), options_.output_dir, loop_->control_state());
  }

  void write_manifest() {
    manifest_.steps = loop_->steps();
    manifest_.time = loop_->time();
    manifest_.write(options_.output_dir / "run.json");
  }

  const Scene& scene_;
  const Plan& plan_;
  const RunOptions& options_;
  std::uint64_t seed_;
  RunManifest manifest_;
  /// Per-step geometry fluid -> ssa: shared memory on this host, else inline.
  GeometryChannel geometry_;
  std::optional<FluidClient> fluid_;
  std::optional<FlowReplay> replay_;  ///< instead of fluid_ (RunOptions::flow_replay)
  std::optional<SsaClient> ssa_;
  std::optional<FrameOutput> frames_;
  std::optional<BodyForceLog> forces_;  ///< scene fluid.body_forces
  std::optional<SplittingLoop> loop_;   ///< after the clients it calls: destroyed first
};

}  // namespace

RunResult run_coupled(const Scene& scene, const Plan& plan, const ServiceEndpoints& endpoints,
                      const RunOptions& options) {
  CoupledRun run(scene, plan, endpoints, options);
  try {
    return run.execute();
  } catch (const std::exception& e) {
    run.fail(e.what());
    throw;
  }
}

}  // namespace sadr::orchestrator
