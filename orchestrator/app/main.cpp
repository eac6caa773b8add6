// SPDX-License-Identifier: MIT
// sadr: the orchestrator CLI. Parses the command line and hands over to commands.cpp.
#include <CLI/CLI.hpp>

#include <cmath>
#include "commands.hpp"
#include "graph_report.hpp"

#include "sadr/common/build_info.hpp"
#include "sadr/common/log.hpp"
#include "sadr/common/openmp_env.hpp"
#include "sadr/common/version.hpp"

using namespace sadr::orchestrator;

namespace {
/// A finite number in [lo, hi], with a short message (CLI11's own ranges print
/// the limits of double with 300 digits).
CLI::Validator finite_range(double lo, double hi, const std::string& what) {
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (text.empty() || *end != '\0' || !std::isfinite(v) || v < lo || v > hi) {
          return "'" + text.substr(0, 32) + "' is out of range; allowed: " + what;
        }
        return {};
      },
      what);
}
}  // namespace

int main(int argc, char** argv) {
  sadr::ensure_passive_openmp_wait(argv);  // see openmp_env.hpp
  CLI::App app{
      std::string("sadr ") + sadr::kVersion +
      ": stochastic advection-diffusion-reaction in particle fluids.\n"
      "A particle fluid (fluid_service; `sadr backends` lists its backends) carries\n"
      "molecules whose reactions and diffusion are simulated exactly (ssa_service:\n"
      "Next Subvolume Method on the particle diffusion graph), coupled by Lie or\n"
      "Strang splitting.\n\n"
      "Examples:\n"
      "  sadr validate examples/static_reaction_diffusion.yaml\n"
      "  sadr run examples/annihilation_1d_stochastic.yaml --output runs/ann17\n"
      "  sadr run examples/annihilation_1d_stochastic.yaml --realizations 100\n"
      "  sadr resume runs/ann17/checkpoint/checkpoint.json\n"
      "  deploy/slurm/submit-ensemble.sh SCENE OUT 100  # Slurm array, then sadr ensemble OUT\n"
      "  sbatch --array=0-99 deploy/slurm/realization.sbatch SCENE OUT; sadr ensemble OUT\n"
      "  sadr run SCENE --set 'reactions[annihilation].rate=0.2'  # override a scene value\n"
      "  sadr sweep sweep.yaml -o sweeps/rate  # points x realizations, docs/sweeps.md\n"
      "  sadr keygen ~/.sadr/client.key  # CURVE keys for services on other hosts, docs/cli.md\n\n"
      "Exit codes: 0 ok, 1 invalid scene/input, 2 usage, 3 service failure,\n"
      "4 numerical failure, 5 I/O failure, 130 interrupted (checkpoint written).\n"
      "Scene format: docs/scene-format.md. Outputs: <output>/run.json, frames/,\n"
      "<name>.pvd (ParaView), checkpoint/, ensemble/ (with --realizations)."};
  app.set_version_flag("--version", std::string("sadr ") + sadr::kBuildVersion);
  app.require_subcommand(1);
  CliOptions o;
  std::string mode = "processes", level = "info";
  bool embedded = false;

  auto add_service_options = [&](CLI::App* cmd) {
    cmd->add_flag("--embedded", embedded,
                  "run the services as threads in this process (inproc transport) instead of "
                  "child processes");
    cmd->add_option("--fluid", o.remote.fluid,
                    "endpoint of a running fluid_service (e.g. tcp://host:5555); with --ssa, "
                    "nothing is launched");
    cmd->add_option("--ssa", o.remote.ssa, "endpoint of a running ssa_service");
    cmd->add_option("--key", o.remote_keys.key,
                    "CURVE key pair of this sadr (sadr keygen FILE) for --fluid/--ssa tcp "
                    "endpoints: encrypted, and only services holding the --server-key answer");
    cmd->add_option("--server-key", o.remote_keys.server_key,
                    "public key of the services (40 characters, or their FILE.pub)");
    cmd->add_option("--fluid-server-key", o.remote_keys.fluid_server_key,
                    "fluid_service's public key, when it differs from --server-key");
    cmd->add_option("--ssa-server-key", o.remote_keys.ssa_server_key,
                    "ssa_service's public key, when it differs from --server-key");
    cmd->add_flag("!--no-shared-memory", o.shared_geometry,
                  "send the per-step particle geometry inline in the messages instead of "
                  "through a shared-memory segment (the default for services launched here)");
    cmd->add_option("--timeout", o.timeout_s, "seconds to wait for a service reply")
        ->check(finite_range(1e-3, 1e6, "0.001 to 1e6 seconds"))
        ->capture_default_str();
    cmd->add_option("--restart-on-failure", o.restarts,
                    "relaunch services that die or hang, from the last checkpoint, up to N times")
        ->check(CLI::Range(0, 1000000));
    cmd->add_option("--stop-at", o.stop_at,
                    "write a checkpoint and stop at this simulated time (resume later)")
        ->check(finite_range(0.0, 1e300, "a finite time >= 0 (and <= the scene's time.end)"));
    cmd->add_option("-o,--output", o.output,
                    "output directory (default: output.directory of the scene, else "
                    "runs/<name>-<UTC time>)");
    auto* overlap_on = cmd->add_flag_callback(
        "--overlap", [&] { o.overlap = OverlapRequest::kOn; },
        "run the SSA stage of coupling step k while the fluid computes step k+1 even "
        "without a spare core (default: only when each realization has a core to spare "
        "for the SSA: hardware threads >= fluid threads + 1; see docs/cli.md)");
    auto* overlap_off = cmd->add_flag_callback(
        "--no-overlap", [&] { o.overlap = OverlapRequest::kOff; },
        "always run the fluid and SSA stages one after the other");
    overlap_on->excludes(overlap_off);
    cmd->add_option("--fluid-threads", o.fluid_threads,
                    "OpenMP threads of fluid_service (default: OMP_NUM_THREADS, else all "
                    "cores); sets SADR_FLUID_THREADS for the services launched here")
        ->check(CLI::Range(1, 4096));
    cmd->add_option("--ssa-threads", o.ssa_threads,
                    "OpenMP threads of ssa_service's graph rebuild (default: OMP_NUM_THREADS, "
                    "else all cores); sets SADR_SSA_THREADS for the services launched here")
        ->check(CLI::Range(1, 4096));
    cmd->add_flag("-q,--quiet", o.quiet,
                  "no progress display, plan or info lines (warnings and errors only; "
                  "--log-level overrides)");
    cmd->add_flag("--no-progress", o.no_progress, "no progress display (plan and logs stay)");
    cmd->add_flag("--allow-large", o.allow_large,
                  "run a scene whose work estimate is above the soft limits (long runs, "
                  "large output, more than half the memory; see docs/cli.md)");
    cmd->add_option("--log-level", level, "error|warn|info|debug")
        ->check(CLI::IsMember({"error", "warn", "info", "debug"}));
  };

  auto* validate =
      app.add_subcommand("validate", "parse and check a scene; exit 0 if valid, 1 if not");
  validate->add_option("scene", o.scene, "scene file (YAML)")->required()->check(CLI::ExistingFile);
  auto add_set_option = [&](CLI::App* cmd) {
    cmd->add_option("--set", o.overrides,
                    "override a scene value before validation, PATH=VALUE (repeatable): "
                    "fluid.sound_speed=20, reactions[annihilation].rate=0.2, "
                    "species[0].diffusivity=0.1 (docs/cli.md)");
  };
  add_set_option(validate);
  validate->add_flag("--strict", o.strict,
                     "refuse the scene (exit 1) when it has warnings: a reaction, initial value, "
                     "boundary or observable that selects no particle, molecules that never "
                     "reach the fluid");

  auto* run = app.add_subcommand("run", "run a scene (one realization, or an ensemble)");
  run->add_option("scene", o.scene, "scene file (YAML)")->required()->check(CLI::ExistingFile);
  add_set_option(run);
  run->add_option("-r,--realizations", o.realizations,
                  "independent realizations with seeds derived from the scene seed; each in "
                  "realization_NNNN/, plus per-frame ensemble mean and variance in ensemble/")
      ->check(CLI::Range(1, 10000));
  run->add_option("-j,--jobs", o.jobs, "realizations run at once (default: number of cores)")
      ->check(CLI::Range(0, 10000));
  run->add_flag("--force", o.force, "overwrite a non-empty output directory");
  run->add_option("--realization", o.realization,
                  "run only realization K (0-based) into OUTPUT/realization_K; 'env' takes K "
                  "from SLURM_ARRAY_TASK_ID or JOB_COMPLETION_INDEX (cluster array jobs; "
                  "combine with 'sadr ensemble OUTPUT')");
  add_service_options(run);
  auto add_retries_option = [&](CLI::App* cmd) {
    cmd->add_option("--retries", o.retries,
                    "ensembles: run a failed realization again up to N more times (as a "
                    "sweep's retries; default 1)")
        ->check(CLI::Range(0, 100));
  };
  add_retries_option(run);

  auto* resume =
      app.add_subcommand("resume", "continue a run from its checkpoint, bit-identically");
  resume
      ->add_option(
          "checkpoint", o.checkpoint,
          "a run's folder (uses its checkpoint/checkpoint.json), the checkpoint directory, "
          "checkpoint.json, or an ensemble folder (sadr run -r: runs the realizations that did "
          "not finish)")
      ->required()
      ->check(CLI::ExistingPath);
  add_service_options(resume);
  add_retries_option(resume);

  auto* ensemble = app.add_subcommand(
      "ensemble",
      "combine OUTPUT/realization_*/frames/*.csv into OUTPUT/ensemble/ (mean, variance)");
  ensemble->add_option("directory", o.directory, "the output directory of the realizations")
      ->required()
      ->check(CLI::ExistingDirectory);

  auto* sweep = app.add_subcommand(
      "sweep",
      "run a parameter sweep (points x realizations, local or Slurm), resumable; "
      "docs/sweeps.md");
  sweep->add_option("sweep", o.sweep, "sweep file (YAML)")->check(CLI::ExistingFile);
  sweep->add_option("--resume", o.resume_dir, "continue the sweep in this directory")
      ->check(CLI::ExistingDirectory);
  sweep->add_flag("--aggregate-only", o.aggregate_only,
                  "only read the runs' results and aggregate (the Slurm aggregation job)");
  sweep->add_option("--executor", o.executor, "local or slurm (default: the sweep file's)")
      ->check(CLI::IsMember({"local", "slurm"}));
  sweep->add_option("--workers", o.workers, "local executor: runs at once (default: cores)")
      ->check(CLI::Range(1, 4096));
  sweep->add_option("-o,--output", o.output,
                    "sweep directory (default: the file's output, else "
                    "sweeps/<file stem>)");
  sweep->add_flag("--force", o.force, "start over in a directory that holds another sweep");
  sweep->add_flag("-q,--quiet", o.quiet, "no per-run lines");
  sweep->add_flag("--dry-run", o.dry_run,
                  "check every point's scene and list the runs and their folders; write and "
                  "start nothing");
  auto* sweep_task =
      app.add_subcommand("sweep-task", "one run of a sweep (the worker command of every executor)");
  sweep_task->add_option("directory", o.directory, "the sweep directory")
      ->required()
      ->check(CLI::ExistingDirectory);
  sweep_task->add_option("--index", o.index,
                         "run index (default: SLURM_ARRAY_TASK_ID, else JOB_COMPLETION_INDEX)");
  sweep_task->add_flag("-q,--quiet", o.quiet, "no plan");
  auto* summary = app.add_subcommand(
      "summary",
      "what a run or ensemble did: species totals at the first and last frame, wall time per "
      "stage, steps, sub-steps, events, outputs (also printed at the end of run/resume unless -q)");
  summary->add_option("directory", o.directory, "the output directory of a run or an ensemble")
      ->required()
      ->check(CLI::ExistingDirectory);

  auto* keygen = app.add_subcommand(
      "keygen",
      "write a CURVE key pair for tcp between sadr and services started by hand: FILE "
      "(mode 0600) and FILE.pub (docs/cli.md, \"Security\")");
  std::string key_file;
  bool show_key = false;
  keygen->add_option("file", key_file, "the key pair file to create (never overwritten)")
      ->required();
  keygen->add_flag("--show", show_key, "print the public key of an existing FILE instead");

  auto* backends = app.add_subcommand(
      "backends", "list the fluid backends, their capabilities and parameters (fluid.parameters)");
  bool markdown = false;
  backends->add_flag("--markdown", markdown, "as the Markdown tables of docs/scene-format.md");

  auto* graph = app.add_subcommand(
      "graph",
      "dump the SSA diffusion graph of a scene (edges, D_ij, jump rates) and its "
      "diagnostics (docs/cli.md)");
  std::string graph_format = "json";
  graph->add_option("scene", o.scene, "scene file (YAML)")->required()->check(CLI::ExistingFile);
  graph->add_option("--format", graph_format, "json (default) or csv")
      ->check(CLI::IsMember({"json", "csv"}));
  graph->add_option("-o,--output", o.output, "write to FILE instead of stdout");
  add_set_option(graph);

  auto* geometry = app.add_subcommand(
      "geometry",
      "write the particles a scene's `geometry` section makes (DIR/particles.csv and .vtu: kind, "
      "surface, volume, density error, regions) and print counts, volumes, density error and "
      "the smallest feature");
  geometry->add_option("scene", o.scene, "scene file (YAML)")->required()->check(CLI::ExistingFile);
  geometry->add_option("-o,--output", o.output, "output directory (default: ./geometry)");
  add_set_option(geometry);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? kExitOk : kExitUsage;
  }
  if (o.quiet && level == "info") level = "warn";
  if (level == "error") sadr::log::set_level(sadr::log::Level::kError);
  if (level == "warn") sadr::log::set_level(sadr::log::Level::kWarn);
  if (level == "debug") sadr::log::set_level(sadr::log::Level::kDebug);
  sadr::log::set_component("sadr");
  if (embedded) o.mode = ServiceMode::kEmbedded;
  if (!o.remote.fluid.empty() || !o.remote.ssa.empty()) {
    if (embedded) {
      std::fprintf(stderr, "sadr: --embedded cannot be combined with --fluid/--ssa\n");
      return kExitUsage;
    }
    o.mode = ServiceMode::kRemote;
  }
  try {
    if (*backends) return cmd_backends(markdown);
    if (*graph) return cmd_graph(o, graph_format);
    if (*geometry) return cmd_geometry(o);
    if (*keygen) return cmd_keygen(key_file, show_key);
    if (*run || *resume) use_remote_keys(o);
    if (*validate) return cmd_validate(o);
    if (*run) return cmd_run(o);
    if (*ensemble) return cmd_ensemble(o);
    if (*summary) return cmd_summary(o);
    if (*sweep) {
      if (o.sweep.empty() == o.resume_dir.empty()) {
        std::fprintf(stderr, "sadr sweep: give either SWEEP.yaml or --resume DIR\n");
        return kExitUsage;
      }
      return cmd_sweep(o);
    }
    if (*sweep_task) return cmd_sweep_task(o);
    return cmd_resume(o);
  } catch (const std::exception& e) {
    return report_failure(e);
  }
}
