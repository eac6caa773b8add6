// SPDX-License-Identifier: MIT
// `sadr resume CHECKPOINT`: a run from its checkpoint, bit-identically; or,
// for an ensemble folder, every realization that did not finish (ensemble_resume.cpp).
#include <cstdio>
#include <filesystem>
#include <memory>

#include "cli.hpp"
#include "commands.hpp"
#include "sadr/orchestrator/checkpoint.hpp"
#include "sadr/orchestrator/flow_replay.hpp"
#include "sadr/orchestrator/run_manifest.hpp"
#include "sadr/orchestrator/scene_loader.hpp"
#include "sadr/orchestrator/scene_messages.hpp"
#include "sadr/orchestrator/scene_override.hpp"
#include "sadr/orchestrator/step_control.hpp"
#include "sadr/orchestrator/sweep_manifest.hpp"

namespace sadr::orchestrator {
namespace fs = std::filesystem;
namespace {

struct ResumeCommandOptions {
  std::string checkpoint;  ///< checkpoint.json, its directory, a run's or an ensemble's folder
  ServiceOptions service;
};

int cmd_resume(const ResumeCommandOptions& c) {
  const ServiceOptions& o = c.service;
  install_signal_handlers();
  if (is_ensemble_dir(c.checkpoint)) return resume_ensemble(o, c.checkpoint);
  // A directory: the checkpoint directory itself, or a run's folder holding checkpoint/.
  fs::path manifest_path = c.checkpoint;
  if (fs::is_directory(manifest_path)) {
    const fs::path here = manifest_path / std::string(kCheckpointManifestName);
    const fs::path in_run = manifest_path / "checkpoint" / std::string(kCheckpointManifestName);
    if (fs::exists(here)) {
      manifest_path = here;
    } else if (fs::exists(in_run)) {
      manifest_path = in_run;
    } else {
      throw InvalidArgument("'" + c.checkpoint + "' holds neither " + here.string() + " nor " +
                            in_run.string() +
                            " (pass a run's folder, its checkpoint directory or its "
                            "checkpoint.json; a run that wrote no checkpoint cannot be resumed)");
    }
  }
  LoadedCheckpoint cp = load_checkpoint(manifest_path, "");
  const fs::path run_dir = manifest_path.parent_path().parent_path();
  // The overrides of the run (run.json) make the same effective scene again.
  const Scene scene =
      load_scene(cp.manifest.scene_path, parse_overrides(read_run_overrides(run_dir)));
  if (scene.source_hash != cp.manifest.scene_hash) {
    throw InvalidArgument("checkpoint '" + c.checkpoint + "' was written for scene '" +
                          cp.manifest.scene_path + "' with hash " + cp.manifest.scene_hash +
                          ", but that file now has hash " + scene.source_hash +
                          " (the scene changed since the run started)");
  }
  // With time.tolerance steps may be as short as the controller's smallest step.
  const double shortest = scene.time.tolerance
                              ? scene.time.coupling_step * StepController::kMinStepFraction
                              : scene.time.coupling_step;
  check_manifest_fits_scene(cp.manifest, scene.time.end, shortest, scene.output.times.size(),
                            scene.seed, manifest_path.string());
  Plan plan = make_plan(scene);
  configure_threads_and_overlap(plan, o, 1);
  print_plan(scene, plan, o);
  check_stop_at(o, scene, cp.manifest.time);
  const fs::path out = o.output.empty() ? run_dir : fs::path(o.output);
  check_work(scene, plan, o, out, 1, 1);
  if (!o.quiet)
    std::fprintf(stderr, "sadr: resuming realization %llu at t = %g (step %llu) into %s\n",
                 static_cast<unsigned long long>(cp.manifest.realization), cp.manifest.time,
                 static_cast<unsigned long long>(cp.manifest.step_index), out.string().c_str());
  RunOptions base;
  base.progress = !o.quiet && !o.no_progress;
  if (const auto f = cp.blobs.find("fluid");
      f != cp.blobs.end() && is_flow_replay_snapshot(f->second.bytes)) {
    // One realization of an ensemble or array (OUTPUT/flow_replay.bin), or a sweep's run
    // (SWEEP_DIR/flows/<fluid key>.bin).
    base.flow_replay = flow_replay_path(run_dir.parent_path());
    const fs::path sweep_dir = run_dir.parent_path().parent_path();
    if (!fs::exists(base.flow_replay) && fs::exists(sweep_dir / std::string(kSweepManifestName))) {
      base.flow_replay = sweep_dir / flow_tape_file(fluid_key(scene, plan));
    }
    if (!o.quiet) {
      std::fprintf(stderr, "sadr: the realization replays the flow in %s\n",
                   base.flow_replay.string().c_str());
    }
  }
  const RunResult r = run_realization(scene, plan, o, cp.manifest.realization, out, &cp, base);
  if (!r.interrupted) summarize_at_end(out, o.quiet);
  return r.interrupted && interrupt_requested() ? kExitInterrupted : kExitOk;
}

}  // namespace

Subcommand add_resume_command(CLI::App& app) {
  auto o = std::make_shared<ResumeCommandOptions>();
  auto* resume =
      app.add_subcommand("resume", "continue a run from its checkpoint, bit-identically");
  resume
      ->add_option(
          "checkpoint", o->checkpoint,
          "a run's folder (uses its checkpoint/checkpoint.json), the checkpoint directory, "
          "checkpoint.json, or an ensemble folder (sadr run -r: runs the realizations that did "
          "not finish)")
      ->required()
      ->check(CLI::ExistingPath);
  add_service_options(resume, o->service);
  add_retries_option(resume, o->service);
  add_flow_replay_option(resume, o->service);
  return {resume, [o] {
            if (const int rc = resolve_service_mode(o->service); rc != kExitOk) return rc;
            use_remote_keys(o->service);
            return cmd_resume(*o);
          }};
}

}  // namespace sadr::orchestrator
