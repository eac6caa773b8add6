// SPDX-License-Identifier: MIT
// Signals, the plan, and one realization with its services (restarts and
// retries: restart_policy.hpp).
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "commands.hpp"
#include "graph_report.hpp"
#include "sadr/common/log.hpp"
#include "sadr/orchestrator/restart_policy.hpp"
#include "sadr/orchestrator/scene_messages.hpp"

namespace sadr::orchestrator {
namespace fs = std::filesystem;
namespace {

std::atomic<bool> g_interrupt{false};
extern "C" void on_signal(int) {
  g_interrupt.store(true);
}

}  // namespace

void install_signal_handlers() {
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  std::signal(SIGPIPE, SIG_IGN);
  // Before starting anything: what runs killed with -9 left behind.
  if (const std::size_t n = remove_traces_of_dead_runs(); n > 0) {
    log::info("removed ", n, " segment(s) or socket directorie(s) of runs that no longer exist");
  }
}

bool interrupt_requested() {
  return g_interrupt.load();
}

std::atomic<bool>& interrupt_flag() {
  return g_interrupt;
}

void print_plan(const Scene& scene, const Plan& plan, const ServiceOptions& o) {
  for (const auto& w : scene.warnings) log::warn(w);
  const GraphReport graph = graph_report(scene, plan);  // SSA graph diagnostics
  if (!graph.warning.empty()) log::warn(scene.name, ": ", graph.warning);
  if (o.quiet) return;
  std::fprintf(stderr, "sadr: scene '%s' (%zu particles, %zu species, %zu reactions), t_end = %g\n",
               scene.name.c_str(), scene.particles.size(), scene.species.size(),
               scene.reactions.size(), scene.time.end);
  try {  // the scene's meaning, whatever file it came from (scene_messages.hpp)
    std::fprintf(stderr, "sadr: scene meaning %s\n", scene_meaning_hash(scene, plan).c_str());
  } catch (const std::exception&) {
    // a scene the services refuse: the run says why, where it builds the same messages
  }
  std::fprintf(stderr, "sadr: plan (services as %s):\n", std::string(to_string(o.mode)).c_str());
  for (const auto& line : plan.lines()) std::fprintf(stderr, "  - %s\n", line.c_str());
  for (const auto& line : graph.lines) std::fprintf(stderr, "  - %s\n", line.c_str());
}

RunResult run_realization(const Scene& scene, const Plan& plan, const ServiceOptions& o,
                          std::uint64_t realization, const fs::path& out,
                          const LoadedCheckpoint* resume, const RunOptions& base) {
  const RestartPolicy policy{o.restarts, o.mode == ServiceMode::kRemote};
  return run_with_restarts(
      policy, realization, out, scene.source_hash, resume,
      [&] {
        Plan launch = plan;  // a replayed flow needs no fluid_service
        if (!base.flow_replay.empty()) launch.fluid_service = false;
        return std::make_unique<ServiceSet>(o.mode, launch, o.remote, std::to_string(realization));
      },
      [&](std::unique_ptr<ServiceSet>& services, const LoadedCheckpoint* from) {
        RunOptions ro = base;
        ro.output_dir = out;
        ro.realization = realization;
        ro.mode = std::string(to_string(o.mode));
        // Services launched here share this host: geometry through shared memory.
        ro.shared_geometry = o.mode != ServiceMode::kRemote && o.shared_geometry;
        ro.timeout = std::chrono::milliseconds(static_cast<long>(o.timeout_s * 1000));
        ro.interrupt = &g_interrupt;
        ServiceSet* set = services.get();
        ro.liveness = [set] { set->check_alive(); };
        ro.resume = from;
        if (o.stop_at >= 0) ro.stop_at = o.stop_at;
        return run_coupled(scene, plan, set->endpoints(), ro);
      });
}

std::optional<FailedRealization> run_ensemble_member(const Scene& scene, const Plan& plan,
                                                     const ServiceOptions& o, int r,
                                                     const fs::path& rd, bool from_checkpoint,
                                                     const RunOptions& base,
                                                     const std::function<void()>& before_attempt,
                                                     RunResult& result) {
  return run_with_retries(
      RetryPolicy{o.retries, from_checkpoint}, r, rd, scene.source_hash, before_attempt,
      [&](const LoadedCheckpoint* resume) {
        result = run_realization(scene, plan, o, static_cast<std::uint64_t>(r), rd, resume, base);
      },
      interrupt_requested);
}

int report_failed_realizations(const fs::path& dir, const std::vector<FailedRealization>& failed) {
  std::fprintf(stderr,
               "sadr: %zu realizations failed (the ensemble/ files count the others in "
               "their realizations column):\n  %-11s %-8s %-4s %s\n",
               failed.size(), "realization", "attempts", "exit", "reason");
  for (const auto& f : failed) {
    std::fprintf(stderr, "  %-11d %-8d %-4d %s\n", f.realization, f.attempts, f.exit_code,
                 f.reason.substr(0, f.reason.find('\n')).c_str());
  }
  std::fprintf(stderr, "sadr: run or resume them with: sadr resume %s\n", dir.string().c_str());
  return kExitServiceFailure;
}

}  // namespace sadr::orchestrator
