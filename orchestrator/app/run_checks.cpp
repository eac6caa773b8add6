// SPDX-License-Identifier: MIT
// The checks and settings before a run: the work estimate (with the fluid
// backend's sub-steps at t = 0), threads and overlap, --stop-at.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <thread>

#include "commands.hpp"
#include "sadr/common/log.hpp"
#include "sadr/fluid/fluid_service.hpp"
#include "sadr/orchestrator/diagnostics.hpp"
#include "sadr/orchestrator/scene_messages.hpp"
#include "sadr/orchestrator/seeds.hpp"
#include "sadr/orchestrator/service_clients.hpp"

namespace sadr::orchestrator {
namespace fs = std::filesystem;
namespace {

/// The fluid backend's sub-steps ahead at t = 0, from the backend itself, started in this
/// process on the run's Init message (fluid::initial_substep_bound: no service, no handler, no
/// serialised message), before any service is started, so that validate and the plan of
/// run/resume can print it. Nothing if the plan does not step the fluid, or if the backend
/// refuses the initial state (the run then fails at the service's init with the service's
/// message, as without this).
std::optional<FluidSubsteps> fluid_substeps_at_t0(const Scene& scene, const Plan& plan) {
  if (!plan.fluid_service || !plan.fluid_stepping) return std::nullopt;
  struct QuietLog {  // the backend's own lines are the service's, printed when it runs
    log::Level saved = log::level();
    QuietLog() { log::set_level(log::Level::kError); }
    ~QuietLog() { log::set_level(saved); }
  } quiet;
  std::optional<FluidSubsteps> out;
  // On a thread of its own, as the embedded service runs: the start sets that thread's OpenMP
  // thread count (SADR_FLUID_THREADS), not this one's.
  std::thread([&] {
    try {
      const fluid::SubstepBound b = fluid::initial_substep_bound(
          make_fluid_init(scene, plan, realization_seed(scene.seed, 0)));
      out = FluidSubsteps{b.limit, b.limit_name, b.dt};
    } catch (const std::exception&) {
      out.reset();  // the run says why, where it builds the same message or starts the backend
    }
  }).join();
  return out;
}

}  // namespace

/// estimate_work() with the backend's sub-steps at t = 0 once the hard limits (memory, disk)
/// allow initialising the backend here and that init fits (in_process_init_fits: otherwise the
/// figure is not computed, and the plan says so).
WorkEstimate estimate_with_backend(const Scene& scene, const Plan& plan, const fs::path& out,
                                   int realizations, int jobs) {
  const MachineLimits machine = machine_limits(out);
  WorkEstimate e = estimate_work(scene, plan, machine, realizations, jobs);
  if (!e.hard.empty()) return e;
  if (!plan.fluid_service || !plan.fluid_stepping) return e;
  const double need = in_process_init_bytes(e, jobs);
  if (!in_process_init_fits(need, machine)) {
    e.substeps_skipped = need;
    return e;
  }
  if (const auto fluid = fluid_substeps_at_t0(scene, plan)) {
    e = estimate_work(scene, plan, machine, realizations, jobs, &*fluid);
  }
  return e;
}

/// The work estimate, printed with the plan, then its limits: hard ones always
/// refuse; soft ones refuse unless --allow-large (then they are warnings).
void check_work(const Scene& scene, const Plan& plan, const ServiceOptions& o, const fs::path& out,
                int realizations, int jobs) {
  const WorkEstimate e = estimate_with_backend(scene, plan, out, realizations, jobs);
  if (!o.quiet) {
    for (const auto& line : e.lines()) std::fprintf(stderr, "  - %s\n", line.c_str());
  }
  enforce_limits(e, o.allow_large);
  for (const auto& line : e.soft) log::warn(line, " (allowed by --allow-large)");
  for (const auto& note : e.notes) log::warn(note);
}

/// OpenMP threads the fluid will use: --fluid-threads, else OMP_NUM_THREADS (its
/// first value), else every hardware thread (OpenMP's default).
int fluid_threads(const ServiceOptions& o, unsigned hardware_threads) {
  if (o.fluid_threads > 0) return o.fluid_threads;
  if (const char* v = std::getenv("SADR_FLUID_THREADS"); v && std::atoi(v) > 0) return std::atoi(v);
  if (const char* v = std::getenv("OMP_NUM_THREADS"); v && std::atoi(v) > 0) return std::atoi(v);
  return static_cast<int>(hardware_threads);
}

/// Per-service thread counts for the services launched here (child processes
/// inherit the environment; embedded handlers read it in this process), then
/// the overlap decision of the plan.
void configure_threads_and_overlap(Plan& plan, const ServiceOptions& o, int jobs) {
  if (o.fluid_threads > 0) setenv("SADR_FLUID_THREADS", std::to_string(o.fluid_threads).c_str(), 1);
  if (o.ssa_threads > 0) setenv("SADR_SSA_THREADS", std::to_string(o.ssa_threads).c_str(), 1);
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  decide_overlap(plan, o.overlap, hw, fluid_threads(o, hw), jobs);
}

/// --stop-at T: finite (the parser checks >= 0) and before the scene's end.
void check_stop_at(const ServiceOptions& o, const Scene& scene, double from) {
  if (o.stop_at < 0) return;
  if (!(o.stop_at > from) || !(o.stop_at <= scene.time.end)) {
    throw InvalidArgument("--stop-at " + format_number(o.stop_at) +
                          " is out of range; allowed: " + format_number(from) +
                          " < T <= " + format_number(scene.time.end) + " (the scene's time.end)");
  }
}

}  // namespace sadr::orchestrator
