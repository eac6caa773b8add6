// SPDX-License-Identifier: MIT
// sadr: the orchestrator CLI. Each subcommand registers its own options (one
// file each, cli.hpp); main() parses and dispatches.
#include <CLI/CLI.hpp>

#include <vector>

#include "cli.hpp"
#include "sadr/common/build_info.hpp"
#include "sadr/common/log.hpp"
#include "sadr/common/openmp_env.hpp"
#include "sadr/common/version.hpp"
#include "sadr/orchestrator/exit_codes.hpp"

using namespace sadr::orchestrator;

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
  // In the order of `sadr --help` (a braced list is evaluated left to right).
  const std::vector<Subcommand> commands{
      add_validate_command(app), add_run_command(app),      add_resume_command(app),
      add_ensemble_command(app), add_sweep_command(app),    add_sweep_task_command(app),
      add_summary_command(app),  add_keygen_command(app),   add_backends_command(app),
      add_graph_command(app),    add_geometry_command(app),
  };
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? kExitOk : kExitUsage;
  }
  sadr::log::set_component("sadr");
  try {
    for (const auto& c : commands) {
      if (*c.cmd) return c.run();
    }
    return kExitUsage;  // not reached: require_subcommand(1)
  } catch (const std::exception& e) {
    return report_failure(e);
  }
}
