// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/flow_replay.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>

#include "sadr/common/status.hpp"
#include "sadr/orchestrator/frame_output.hpp"
#include "sadr/orchestrator/run_manifest.hpp"
#include "sadr/orchestrator/scene_messages.hpp"
#include "sadr/orchestrator/seeds.hpp"
#include "sadr/orchestrator/service_clients.hpp"
#include "sadr/orchestrator/splitting_loop.hpp"
#include "sadr/wire/convert.hpp"

namespace sadr::orchestrator {
namespace {

constexpr std::string_view kSnapshotPrefix = "sadr-flow-replay-position ";

std::string names(const std::vector<std::string>& v) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + v[i];
  return s + "]";
}

std::string describe(const FlowRecord& r) {
  char buf[96];
  switch (r.call) {
    case FlowCall::kAdvance:
      std::snprintf(buf, sizeof buf, "advance(step %llu, dt %.17g, geometry %s, species ",
                    static_cast<unsigned long long>(r.step_index), r.dt,
                    r.want_geometry ? "yes" : "no");
      return buf + names(r.species) + ")";
    case FlowCall::kGeometry:
      return "geometry()";
    case FlowCall::kFrame:
      return "frame(" + names(r.species) + ")";
  }
  return "?";
}

ParticleState arrays_of(const Geometry& g, const char* call) {
  if (g.generation() > 0 || !g.arrays()) {
    throw Error(StatusCode::kInternal, std::string("flow recording: ") + call +
                                           " returned no inline geometry (shared memory is off "
                                           "while recording)");
  }
  return wire::from_proto(*g.arrays(), "fluid_service geometry");
}

Geometry inline_geometry(const ParticleState& p) {
  auto arrays = std::make_shared<common::v1::ParticleState>();
  wire::to_proto(p, *arrays, !p.velocities.empty());
  return Geometry::inline_arrays(std::move(arrays));
}

/// The SSA of the fluid-only pass: nothing to do, nothing to say.
class NoSsa final : public SsaService {
 public:
  SsaStep advance(std::uint64_t, double t_end, Geometry, const std::vector<std::string>&,
                  const SpeciesConcentrations&) override {
    SsaStep s;
    s.time = t_end;
    return s;
  }
  SpeciesCounts counts(const std::vector<std::string>&) override { return {}; }
  std::string snapshot(std::uint64_t) override { return {}; }
  void restore(const std::string&) override {}
};

}  // namespace

FluidStep FlowRecorder::advance(std::uint64_t step_index, double dt, bool want_geometry,
                                const SpeciesCounts& counts,
                                const std::vector<std::string>& return_concentrations) {
  if (!counts.empty()) {
    throw Error(StatusCode::kInternal, "flow recording: the fluid reads copy numbers");
  }
  FluidStep step = inner_.advance(step_index, dt, want_geometry, counts, return_concentrations);
  FlowRecord r;
  r.call = FlowCall::kAdvance;
  r.step_index = step_index;
  r.dt = dt;
  r.want_geometry = want_geometry;
  r.species = return_concentrations;
  r.time = step.time;
  r.substeps = step.substeps;
  r.stable_time_step = step.stable_time_step;
  r.limiting_criterion = step.limiting_criterion;
  r.moved = step.particles_moved;
  r.has_particles = !step.geometry.empty();
  if (r.has_particles) r.particles = arrays_of(step.geometry, "advance");
  r.concentrations = step.concentrations;
  tape_.append(r);
  return step;
}

Geometry FlowRecorder::geometry() {
  Geometry g = inner_.geometry();
  FlowRecord r;
  r.call = FlowCall::kGeometry;
  r.has_particles = true;
  r.particles = arrays_of(g, "geometry");
  tape_.append(r);
  return g;
}

FluidFrame FlowRecorder::frame(const std::vector<std::string>& species) {
  FluidFrame f = inner_.frame(species);
  FlowRecord r;
  r.call = FlowCall::kFrame;
  r.species = species;
  r.has_particles = true;
  r.particles = f.particles;
  r.concentrations = f.concentrations;
  tape_.append(r);
  return f;
}

std::string FlowRecorder::snapshot(std::uint64_t) {
  throw Error(StatusCode::kInternal, "flow recording: no checkpoints in the fluid-only pass");
}

void FlowRecorder::restore(const std::string&) {
  throw Error(StatusCode::kInternal, "flow recording: no checkpoints in the fluid-only pass");
}

FlowReplay::FlowReplay(const std::filesystem::path& path, const std::string& fluid_key)
    : tape_(path, fluid_key) {}

FlowRecord FlowReplay::expect(FlowCall call, const std::string& asked) {
  const std::uint64_t k = tape_.position().record;
  FlowRecord r = tape_.next();
  if (r.call != call || describe(r) != asked) {
    throw FailedPrecondition("flow replay: fluid call " + std::to_string(k) + " of this run is " +
                             asked + ", the flow replay file recorded " + describe(r) +
                             " there; the file does not match this run (run again with "
                             "--no-flow-replay, or remove the file to record it again)");
  }
  return r;
}

FluidStep FlowReplay::advance(std::uint64_t step_index, double dt, bool want_geometry,
                              const SpeciesCounts& counts,
                              const std::vector<std::string>& return_concentrations) {
  if (!counts.empty()) {
    throw FailedPrecondition("flow replay: the fluid would read copy numbers (back-transfer)");
  }
  FlowRecord q;
  q.step_index = step_index;
  q.dt = dt;
  q.want_geometry = want_geometry;
  q.species = return_concentrations;
  FlowRecord r = expect(FlowCall::kAdvance, describe(q));
  FluidStep step;
  step.time = r.time;
  step.substeps = r.substeps;
  step.stable_time_step = r.stable_time_step;
  step.limiting_criterion = r.limiting_criterion;
  step.particles_moved = r.moved;
  if (r.has_particles) step.geometry = inline_geometry(r.particles);
  step.concentrations = std::move(r.concentrations);
  return step;
}

Geometry FlowReplay::geometry() {
  FlowRecord q;
  q.call = FlowCall::kGeometry;
  return inline_geometry(expect(FlowCall::kGeometry, describe(q)).particles);
}

FluidFrame FlowReplay::frame(const std::vector<std::string>& species) {
  FlowRecord q;
  q.call = FlowCall::kFrame;
  q.species = species;
  FlowRecord r = expect(FlowCall::kFrame, describe(q));
  return FluidFrame{std::move(r.particles), std::move(r.concentrations)};
}

std::string FlowReplay::snapshot(std::uint64_t) {
  const FlowTapePosition p = tape_.position();
  return std::string(kSnapshotPrefix) + std::to_string(p.record) + " " + std::to_string(p.offset);
}

void FlowReplay::restore(const std::string& snapshot) {
  unsigned long long record = 0, offset = 0;
  if (!is_flow_replay_snapshot(snapshot) ||
      std::sscanf(snapshot.c_str() + kSnapshotPrefix.size(), "%llu %llu", &record, &offset) != 2) {
    throw InvalidArgument(
        "flow replay: the checkpoint's fluid state is not a place in a flow replay file "
        "(this realization stepped its own fluid: resume it with --no-flow-replay)");
  }
  tape_.seek({record, offset});
}

bool is_flow_replay_snapshot(const std::string& bytes) {
  return bytes.rfind(kSnapshotPrefix, 0) == 0;
}

RecordedFlow record_flow(const Scene& scene, const Plan& plan, const std::string& fluid_endpoint,
                         const RecordFlowOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::uint64_t seed = realization_seed(scene.seed, 0);
  FluidClient fluid(fluid_endpoint, options.timeout);
  if (options.liveness) fluid.set_liveness_check(options.liveness);
  fluid.set_run_id(scene.source_hash + "/" + std::to_string(seed));
  fluid.init(make_fluid_init(scene, plan, seed));  // geometry inline: no channel
  FlowTapeWriter tape(options.path, fluid_key(scene, plan), scene.particles.size());
  FlowRecorder recorder(fluid, tape);
  NoSsa ssa;
  RunManifest stats;
  LoopSettings settings = make_loop_settings(scene, plan);
  settings.checkpoint_every = 0.0;
  settings.overlap = false;
  SplittingLoop loop(&recorder, &ssa, settings, stats);
  const std::vector<std::string> species = frame_fluid_species(scene);
  if (!scene.output.times.empty() && std::abs(scene.output.times.front()) <=
                                         time_snap(0.0, scene.time.coupling_step, scene.time.end)) {
    recorder.frame(species);  // the frame at t = 0 (CoupledRun::execute)
  }
  LoopHooks hooks;
  hooks.frame = [&](std::size_t, double) { recorder.frame(species); };
  hooks.stop_requested = [&] { return options.interrupt && options.interrupt->load(); };
  RecordedFlow out;
  const bool interrupted = loop.run(hooks);
  out.records = tape.records();
  if (!interrupted) {
    out.bytes = tape.finish();
    out.complete = true;
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace sadr::orchestrator
