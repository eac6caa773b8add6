// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/coupled_run.hpp"

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <exception>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <thread>

#include <google/protobuf/io/coded_stream.h>
#include <google/protobuf/io/zero_copy_stream_impl_lite.h>
#include <google/protobuf/message.h>

#include "sadr/common/log.hpp"
#include "sadr/orchestrator/frame_writers.hpp"
#include "sadr/orchestrator/progress.hpp"
#include "sadr/orchestrator/run_manifest.hpp"
#include "sadr/orchestrator/scene_messages.hpp"
#include "sadr/orchestrator/seeds.hpp"
#include "sadr/orchestrator/service_clients.hpp"
#include "sadr/orchestrator/splitting.hpp"
#include "sadr/wire/convert.hpp"
#include "sadr/wire/shared_geometry.hpp"

namespace sadr::orchestrator {
namespace {

using Clock = std::chrono::steady_clock;

/// Adds the wall-clock time of its scope to timings[key] [s].
class ScopedTimer {
 public:
  ScopedTimer(std::map<std::string, double>& timings, const char* key)
      : timings_(timings), key_(key), t0_(Clock::now()) {}
  ~ScopedTimer() { timings_[key_] += std::chrono::duration<double>(Clock::now() - t0_).count(); }

 private:
  std::map<std::string, double>& timings_;
  const char* key_;
  Clock::time_point t0_;
};

/// One job at a time on a persistent thread: the SSA stage of the overlapped
/// loop. The job owns the SSA client while it runs; the mutex hand-over orders
/// every use of the client (and its ZeroMQ socket) between the two threads.
class Worker {
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

/// The message's bytes with map entries in key order (protobuf's default order of
/// map fields varies between runs): equal states give byte-identical checkpoint blobs.
std::string deterministic_bytes(const google::protobuf::Message& message) {
  std::string out;
  {
    google::protobuf::io::StringOutputStream stream(&out);
    google::protobuf::io::CodedOutputStream coded(&stream);
    coded.SetSerializationDeterministic(true);
    message.SerializeToCodedStream(&coded);
  }
  return out;
}

std::string frame_name(std::size_t index, const char* ext) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "frames/frame_%06zu.%s", index, ext);
  return buf;
}

class CoupledRun {
 public:
  CoupledRun(const Scene& scene, const Plan& plan, const ServiceEndpoints& endpoints,
             const RunOptions& options)
      : scene_(scene),
        plan_(plan),
        options_(options),
        seed_(realization_seed(scene.seed, options.realization)),
        pvd_(options.output_dir / (scene.name.empty() ? "frames.pvd" : scene.name + ".pvd")) {
    if (plan_.fluid_service) {
      if (endpoints.fluid.empty()) throw FailedPrecondition("the plan needs fluid_service");
      fluid_.emplace(endpoints.fluid, options.timeout);
      if (options.liveness) fluid_->set_liveness_check(options.liveness);
    }
    if (plan_.ssa_service) {
      if (endpoints.ssa.empty()) throw FailedPrecondition("the plan needs ssa_service");
      ssa_.emplace(endpoints.ssa, options.timeout);
      if (options.liveness) ssa_->set_liveness_check(options.liveness);
    }
    particles_ = scene_.particles;
    if (options.shared_geometry && fluid_ && ssa_ && plan_.particles_to_ssa_each_step) {
      try {
        shm_ = wire::SharedGeometry::create(scene_.particles.size());
        log::info("geometry to ssa_service through shared memory ", shm_->name());
      } catch (const Error& e) {
        log::warn("no shared-memory segment for the geometry (", e.what(),
                  "); sending it inline in the messages instead");
      }
    }
    manifest_.scene_path = scene_.source_path.string();
    manifest_.scene_hash = scene_.source_hash;
    manifest_.overrides = scene_.overrides;
    manifest_.scene_seed = scene_.seed;
    manifest_.realization = options.realization;
    manifest_.seed = seed_;
    manifest_.mode = options.mode;
    manifest_.started_utc = utc_now_iso8601();
    manifest_.plan = plan_.to_json();
    // The same condition as Plan::overlap_allowed, checked again against what
    // this run actually has (both clients).
    overlap_ = plan_.overlap && plan_.overlap_allowed && fluid_ && ssa_ && plan_.fluid_stepping &&
               !plan_.back_transfer && scene_.time.splitting == Splitting::kLie;
    ensure_directory(options.output_dir / "frames");
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
    Progress progress(t_, scene_.time.end, options_.progress_label, options_.progress);
    double next_checkpoint = next_checkpoint_after(t_);
    double last_checkpoint_time = -1.0;
    const auto& outputs = scene_.output.times;
    const double tau = scene_.time.coupling_step, t_end = scene_.time.end;
    auto stop_requested = [&] { return options_.interrupt && options_.interrupt->load(); };
    auto reaches_stop_at = [&](double t) {
      return t >= options_.stop_at - time_snap(t, tau, t_end);
    };
    // Nothing moves (plan.frame_to_frame): one step per output/checkpoint/stop time.
    const FrameToFrame landings{scene_.output.checkpoint_every, options_.stop_at};
    const FrameToFrame* ftf = plan_.frame_to_frame ? &landings : nullptr;
    if (overlap_) worker_.emplace();
    const auto loop_t0 = Clock::now();
    try {
      while (auto cs = next_coupling_step(t_, tau, t_end, outputs, ftf)) {
        // Overlap: leave the SSA stage of this step running while the fluid
        // computes the next one, unless the step ends where both services are
        // needed at once (a frame, a checkpoint, the stop time, the end) or a
        // stop was requested. The same stages, in the same order per service.
        const bool defer_ssa = overlap_ && !cs->output && !cs->last && cs->end < next_checkpoint &&
                               !reaches_stop_at(cs->end) && !stop_requested() &&
                               next_coupling_step(cs->end, tau, t_end, outputs, ftf);
        step(*cs, defer_ssa);
        if (cs->output) {
          write_frame(frame_index(cs->end), cs->end);
          ++result.frames;
        }
        const bool stop = stop_requested() || reaches_stop_at(t_);
        if (stop || t_ >= next_checkpoint) {
          result.last_checkpoint = checkpoint();
          last_checkpoint_time = t_;
          next_checkpoint = next_checkpoint_after(t_);
        }
        progress.update(t_, step_);
        if (stop) {
          result.interrupted = true;
          break;
        }
      }
      drain();
    } catch (...) {
      drain_after_failure();
      throw;
    }
    manifest_.timings_s["coupling_loop"] +=
        std::chrono::duration<double>(Clock::now() - loop_t0).count();
    progress.finish(t_, step_);
    if (!result.interrupted && scene_.output.checkpoint_every > 0 && last_checkpoint_time != t_) {
      result.last_checkpoint = checkpoint();
    }
    manifest_.status = result.interrupted ? "interrupted" : "ok";
    manifest_.finished_utc = utc_now_iso8601();
    write_manifest();
    result.steps = step_;
    result.time = t_;
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
  void init_services() {
    ScopedTimer timer(manifest_.timings_s, "init");
    if (fluid_) {
      const auto rep = fluid_->init(make_fluid_init(scene_, plan_, seed_));
      log::debug("fluid_service ready: stable dt ", rep.stable_time_step(), " (",
                 rep.limiting_criterion(), ")");
    }
    if (ssa_) ssa_->init(make_ssa_init(scene_, plan_, seed_, particles_));
  }

  void restore(const LoadedCheckpoint& cp) {
    ScopedTimer timer(manifest_.timings_s, "restore");
    auto snapshot_of = [&](const char* service) {
      const auto it = cp.blobs.find(service);
      if (it == cp.blobs.end()) {
        throw InvalidArgument(std::string("checkpoint has no '") + service + "' blob");
      }
      common::v1::Snapshot snap;
      if (!snap.ParseFromString(it->second.bytes)) {
        throw InvalidArgument(std::string("checkpoint '") + service + "' blob is corrupt");
      }
      return snap;
    };
    if (fluid_) fluid_->restore(snapshot_of("fluid"));
    if (ssa_) ssa_->restore(snapshot_of("ssa"));
    t_ = cp.manifest.time;
    step_ = cp.manifest.step_index;
    if (fluid_) refresh_particles();
    // Frames up to t_ were written before the checkpoint: list them again.
    for (std::size_t k = 0; k < scene_.output.times.size(); ++k) {
      if (scene_.output.times[k] > t_) break;
      register_frame_files(k, scene_.output.times[k], /*written_now=*/false);
    }
    log::info("resumed at t = ", t_, " after ", step_, " coupling steps");
  }

  void refresh_particles() {
    fluid::v1::GetStateRequest req;
    const auto st = fluid_->get_state(req);
    particles_ = wire::from_proto(st.particles(), "fluid_service state");
  }

  /// An SSA stage ready to send: the request and where its geometry is.
  struct SsaStage {
    ssa::v1::AdvanceRequest req;
    std::uint64_t shm_generation = 0;  ///< > 0: the geometry is in shm_
  };
  /// What the SSA call reports, added to the manifest by the main thread.
  struct SsaTimes {
    double call = 0.0, graph = 0.0, nsm = 0.0;
    std::uint64_t shm_generation = 0;
  };

  /// One coupling step. With `defer_ssa` (Lie, overlap on) the SSA stage is
  /// left running on the worker thread; the next call to step() (or drain())
  /// waits for it after its fluid stage.
  void step(const CouplingStep& cs, bool defer_ssa) {
    const auto stages =
        coupling_stages(scene_.time.splitting, cs.begin, cs.end, plan_.fluid_stepping, !!ssa_);
    const std::uint64_t calls = std::max(1, plan_.fluid_calls_per_step);
    std::uint64_t fluid_call = 0;
    bool moved = false;
    // Positions, densities and masses for the SSA, returned by the fluid call
    // just before an SSA stage (one round trip instead of Advance + GetState).
    std::optional<common::v1::ParticleState> geometry;
    std::uint64_t shm_generation = 0;  // > 0: the geometry is in shm_ instead
    for (std::size_t k = 0; k < stages.size(); ++k) {
      const Stage& stage = stages[k];
      if (stage.op == Operator::kFluid) {
        if (plan_.back_transfer) back_transfer();
        ScopedTimer timer(manifest_.timings_s, "fluid");
        fluid::v1::AdvanceRequest req;
        req.set_run_id(run_id());
        req.set_step_index(step_ * calls + fluid_call++);
        req.set_time_step(stage.length());
        req.set_return_state(ssa_ && plan_.particles_to_ssa_each_step && k + 1 < stages.size() &&
                             stages[k + 1].op != Operator::kFluid);
        if (req.return_state() && shm_) req.set_geometry_shm(shm_->name());
        auto rep = fluid_->advance(req);
        manifest_.timings_s["fluid_compute"] += rep.compute_seconds();
        manifest_.fluid_substeps += rep.substeps();
        moved = rep.particles_moved() || moved;
        shm_generation = rep.geometry_generation();
        if (rep.has_particles()) {
          geometry = std::move(*rep.mutable_particles());
        } else {
          geometry.reset();
        }
      } else {
        // The SSA stage of the previous step (overlapped with the fluid stage
        // just done) comes first: exposed time, the SSA not hidden by the fluid.
        drain();
        ScopedTimer exposed(manifest_.timings_s, "ssa_wait");
        SsaStage ssa;
        ssa.req.set_run_id(run_id());
        ssa.req.set_step_index(step_);
        ssa.req.set_t_end(stage.end);
        if (moved && plan_.particles_to_ssa_each_step) {
          ScopedTimer timer(manifest_.timings_s, "transfer");
          if (shm_generation > 0) {
            ssa.req.set_geometry_shm(shm_->name());
            ssa.req.set_geometry_generation(shm_generation);
            ssa.shm_generation = shm_generation;
          } else if (geometry) {
            *ssa.req.mutable_particles() = std::move(*geometry);
          } else {
            fluid::v1::GetStateRequest gs;
            auto st = fluid_->get_state(gs);
            *ssa.req.mutable_particles() = std::move(*st.mutable_particles());
          }
          moved = false;
        }
        geometry.reset();
        shm_generation = 0;
        if (defer_ssa && k + 1 == stages.size()) {
          pending_times_ = SsaTimes{};
          worker_->submit([this, s = std::move(ssa)] { pending_times_ = run_ssa(s); });
          pending_ = true;
          ++manifest_.overlapped_steps;
        } else {
          add_ssa_times(run_ssa(ssa));
        }
      }
    }
    t_ = cs.end;
    ++step_;
  }

  /// The SSA call of one stage (main thread, or the worker when overlapped:
  /// touches only ssa_ and its own result).
  SsaTimes run_ssa(const SsaStage& s) {
    const auto t0 = Clock::now();
    const auto rep = ssa_->advance(s.req);
    SsaTimes times;
    times.call = std::chrono::duration<double>(Clock::now() - t0).count();
    times.graph = rep.graph_seconds();
    times.nsm = rep.nsm_seconds();
    times.shm_generation = s.shm_generation;
    return times;
  }

  void add_ssa_times(const SsaTimes& times) {
    manifest_.timings_s["ssa"] += times.call;
    manifest_.timings_s["ssa_graph"] += times.graph;
    manifest_.timings_s["ssa_nsm"] += times.nsm;
    // Both services have mapped the segment now: drop its name, so that
    // nothing is left in /dev/shm whatever happens next (idempotent).
    if (times.shm_generation > 0) shm_->unlink();
  }

  /// Waits for the SSA stage left running by step() (if any); rethrows its error.
  void drain() {
    if (!pending_) return;
    ScopedTimer exposed(manifest_.timings_s, "ssa_wait");
    pending_ = false;
    worker_->wait();
    add_ssa_times(pending_times_);
  }

  /// After a failure on the main thread: joins the SSA stage in flight (its own
  /// error, if any, is logged; the main thread's error is the one reported).
  void drain_after_failure() noexcept {
    if (!pending_) return;
    pending_ = false;
    try {
      worker_->wait();
    } catch (const std::exception& e) {
      log::warn("the overlapped ssa_service call failed too: ", e.what());
    } catch (...) {
    }
  }

  /// Copy numbers of the species a fluid term depends on -> concentrations X / V.
  void back_transfer() {
    ScopedTimer timer(manifest_.timings_s, "back_transfer");
    refresh_particles();
    ssa::v1::GetCountsRequest req;
    for (const auto& s : plan_.back_transfer_species) req.add_species(s);
    const auto counts = ssa_->get_counts(req);
    fluid::v1::SetSpeciesRequest set;
    for (const auto& f : counts.counts().species()) {
      auto* c = set.mutable_concentrations()->add_species();
      c->set_name(f.name());
      auto* values = c->mutable_concentrations();
      values->Reserve(f.counts_size());
      for (int i = 0; i < f.counts_size(); ++i) {
        values->Add(static_cast<double>(f.counts(i)) /
                    particles_.volume(static_cast<std::size_t>(i)));
      }
    }
    fluid_->set_species(set);
  }

  std::size_t frame_index(double t) const {
    const auto& times = scene_.output.times;
    const auto it = std::lower_bound(times.begin(), times.end(), t);
    return static_cast<std::size_t>(it - times.begin());
  }

  void write_frame(std::size_t index, double t) {
    drain();  // both services at the same time
    ScopedTimer timer(manifest_.timings_s, "output");
    ParticleState state = particles_;
    std::vector<SpeciesColumn> columns;
    std::map<std::string, std::vector<double>> values;
    if (fluid_) {
      fluid::v1::GetStateRequest req;
      req.set_velocities(true);
      for (const auto& name : scene_.output.species) {
        const Species* s = scene_.find_species(name);
        if (s && !s->stochastic) req.add_species(name);
      }
      const auto st = fluid_->get_state(req);
      state = wire::from_proto(st.particles(), "fluid_service state");
      for (const auto& f : st.concentrations().species()) {
        values[f.name()].assign(f.concentrations().begin(), f.concentrations().end());
      }
    }
    if (ssa_) {
      ssa::v1::GetCountsRequest req;
      for (const auto& name : scene_.output.species) {
        const Species* s = scene_.find_species(name);
        if (s && s->stochastic) req.add_species(name);
      }
      if (req.species_size() > 0) {
        const auto counts = ssa_->get_counts(req);
        for (const auto& f : counts.counts().species()) {
          auto& v = values[f.name()];
          v.resize(static_cast<std::size_t>(f.counts_size()));
          for (int i = 0; i < f.counts_size(); ++i)
            v[static_cast<std::size_t>(i)] = static_cast<double>(f.counts(i));
        }
      }
    }
    for (const auto& name : scene_.output.species) {
      auto it = values.find(name);
      if (it != values.end()) columns.push_back(SpeciesColumn{name, std::move(it->second)});
    }
    if (state.velocities.empty()) state.velocities.assign(3 * state.size(), 0.0);
    for (OutputFormat f : scene_.output.formats) {
      const auto dir = options_.output_dir;
      switch (f) {
        case OutputFormat::kVtu:
          write_vtu(dir / frame_name(index, "vtu"), t, state, columns, scene_.output.vtk_encoding);
          break;
        case OutputFormat::kVtp:
          write_vtp(dir / frame_name(index, "vtp"), t, state, columns, scene_.output.vtk_encoding);
          break;
        case OutputFormat::kCsv:
          write_frame_csv(dir / frame_name(index, "csv"), t, state, columns);
          break;
      }
    }
    register_frame_files(index, t, /*written_now=*/true);
    if (options_.on_frame) options_.on_frame(index, t, columns);
    manifest_.steps = step_;
    manifest_.time = t_;
    write_manifest();
  }

  void register_frame_files(std::size_t index, double t, bool written_now) {
    (void)written_now;
    const auto& formats = scene_.output.formats;
    auto has = [&](OutputFormat f) {
      return std::find(formats.begin(), formats.end(), f) != formats.end();
    };
    if (has(OutputFormat::kVtu)) {
      pvd_.add(t, options_.output_dir / frame_name(index, "vtu"));
    } else if (has(OutputFormat::kVtp)) {
      pvd_.add(t, options_.output_dir / frame_name(index, "vtp"));
    }
    for (OutputFormat f : formats) {
      const char* ext = f == OutputFormat::kVtu ? "vtu" : f == OutputFormat::kVtp ? "vtp" : "csv";
      manifest_.frames.push_back(frame_name(index, ext));
    }
  }

  double next_checkpoint_after(double t) const {
    const double every = scene_.output.checkpoint_every;
    if (!(every > 0)) return std::numeric_limits<double>::infinity();
    const double snap = time_snap(t, scene_.time.coupling_step, scene_.time.end);
    return (std::floor((t + snap) / every) + 1) * every - snap;
  }

  std::filesystem::path checkpoint() {
    drain();  // both services at the same time
    ScopedTimer timer(manifest_.timings_s, "checkpoint");
    CheckpointManifest m;
    m.scene_path = std::filesystem::absolute(scene_.source_path).string();
    m.scene_hash = scene_.source_hash;
    m.seed = seed_;
    m.realization = options_.realization;
    m.step_index = step_;
    m.time = t_;
    std::map<std::string, ServiceBlob> blobs;
    if (fluid_) {
      blobs["fluid"] =
          ServiceBlob{scene_.fluid.backend, deterministic_bytes(fluid_->snapshot(step_))};
    }
    if (ssa_) blobs["ssa"] = ServiceBlob{"nsm", deterministic_bytes(ssa_->snapshot(step_))};
    const auto dir = options_.output_dir / "checkpoint";
    write_checkpoint(dir, m, blobs);
    log::debug("checkpoint at t = ", t_, " (step ", step_, ")");
    return dir / std::string(kCheckpointManifestName);
  }

  void write_manifest() {
    manifest_.steps = step_;
    manifest_.time = t_;
    manifest_.write(options_.output_dir / "run.json");
  }

  std::string run_id() const { return scene_.source_hash + "/" + std::to_string(seed_); }

  const Scene& scene_;
  const Plan& plan_;
  const RunOptions& options_;
  std::uint64_t seed_;
  std::optional<FluidClient> fluid_;
  std::optional<SsaClient> ssa_;
  /// Per-step geometry fluid -> ssa on this host (RunOptions::shared_geometry).
  std::optional<wire::SharedGeometry> shm_;
  ParticleState particles_;
  /// SSA step k runs on worker_ while the fluid computes step k + 1 (plan_.overlap).
  bool overlap_ = false;
  bool pending_ = false;          ///< an SSA stage runs on worker_
  SsaTimes pending_times_{};      ///< written by the worker's job, read after wait()
  std::optional<Worker> worker_;  ///< after what its jobs use: destroyed (joined) first
  double t_ = 0.0;
  std::uint64_t step_ = 0;
  RunManifest manifest_;
  PvdCollection pvd_;
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
