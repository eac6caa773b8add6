// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/work_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "sadr/common/status.hpp"
#include "sadr/fluid/backend_schema.hpp"
#include "sadr/orchestrator/diagnostics.hpp"

namespace sadr::orchestrator {

namespace {

/// "42 s", "3.5 min", "2.1 h", "4.2 days".
std::string duration_text(double seconds) {
  char buf[48];
  if (seconds < 90) {
    std::snprintf(buf, sizeof buf, "%.2g s", seconds);
  } else if (seconds < 5400) {
    std::snprintf(buf, sizeof buf, "%.2g min", seconds / 60);
  } else if (seconds < 172800) {
    std::snprintf(buf, sizeof buf, "%.2g h", seconds / 3600);
  } else {
    std::snprintf(buf, sizeof buf, "%.2g days", seconds / 86400);
  }
  return buf;
}

std::string bytes_text(double b) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  int u = 0;
  while (b >= 1024.0 && u < 6) {
    b /= 1024.0;
    ++u;
  }
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3g %s", b, units[u]);
  return std::isfinite(b) ? buf : std::string("unlimited");
}

std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

/// Bytes of one frame per particle and format, measured on the writers'
/// output at 1e4 particles with 1 and 4 species (2D, thermal noise: full
/// precision everywhere): csv 119 + 5/species, binary vtu 90 + 8/species,
/// ascii vtu 211 + 15/species; rounded up here, plus a header.
double frame_bytes(const Scene& s, double particles) {
  const double species = static_cast<double>(s.output.species.size());
  double per_particle = 0;
  for (const auto f : s.output.formats) {
    if (f == OutputFormat::kCsv) {
      per_particle += 125.0 + 8.0 * species;
    } else if (s.output.vtk_encoding == VtkEncoding::kBinary) {
      per_particle += 92.0 + 8.0 * species;
    } else {
      per_particle += 215.0 + 16.0 * species;
    }
  }
  return 4096.0 + per_particle * particles;
}

/// SSA events per unit time at t = 0: every molecule jumps at about
/// 2 d kappa / dx^2, plus the mass-action propensities of the reactions.
double ssa_event_rate(const Scene& s, double& molecules) {
  const auto& p = s.particles;
  const double n = static_cast<double>(p.size());
  double volume = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kind(i) == ParticleKind::kFluid) volume += p.volume(i);
  }
  const int d = std::max(1, s.box.dimension);
  const double dx = s.lattice_spacing > 0
                        ? s.lattice_spacing
                        : std::pow(std::max(volume, 1e-300) / std::max(n, 1.0), 1.0 / d);
  std::map<std::string, double> total;
  double rate = 0;
  molecules = 0;
  for (const auto& sp : s.species) {
    if (!sp.stochastic) continue;
    double sum = 0;
    for (const double c : sp.initial) sum += c;
    total[sp.name] = sum;
    molecules += sum;
    rate += sum * 2.0 * d * sp.diffusivity / (dx * dx);
  }
  for (const auto& rx : s.reactions) {
    if (!rx.stochastic) continue;
    double a = rx.rate;
    if (rx.order() == 0) a *= volume;
    for (const auto& e : rx.reactants) {
      for (std::uint32_t k = 0; k < e.count; ++k) a *= total[e.species];
    }
    if (rx.order() == 2) a /= std::max(volume, 1e-300);
    rate += a;
  }
  return rate;
}

}  // namespace

std::string FluidSubsteps::criterion() const {
  return max_substep == stable_time_step ? limiting_criterion : std::string("max_time_step");
}

namespace {

/// The wall-time part of the estimate (WorkEstimate::wall_seconds), from the counts above and
/// the calibrated costs; nothing when the fluid steps but its sub-steps are not known.
void estimate_time(const Scene& s, const Plan& plan, WorkEstimate& e, double r, double j) {
  if (plan.fluid_stepping && e.substeps_per_step <= 0) return;
  const auto d = static_cast<std::size_t>(std::clamp(s.box.dimension, 1, 3) - 1);
  const auto* backend = sadr::fluid::schema::find(s.fluid.backend);
  const double fluid_ns =
      backend ? backend->cost.substep_ns[d] : sadr::fluid::schema::CostPerParticle{}.substep_ns[d];
  const double runs = r / j;  // realizations run `jobs` at a time
  const double fluid =
      plan.fluid_stepping ? e.particles * e.fluid_substeps * fluid_ns * 1e-9 * runs : 0.0;
  const double graph = plan.ssa_service && moves_particles(s.fluid.backend)
                           ? e.particles * e.coupling_steps * kGraphRebuildNs[d] * 1e-9 * runs
                           : 0.0;
  const double ssa = e.events * kSsaEventNs * 1e-9 / j;
  const double frames =
      e.frames * (kFrameSeconds + e.particles * kFrameNsPerParticle * 1e-9) * runs;
  const double steps = e.coupling_steps * kStepSeconds * runs;
  e.time_parts = {
      {"fluid", fluid}, {"graph", graph}, {"ssa", ssa}, {"frames", frames}, {"steps", steps}};
  e.wall_seconds = fluid + graph + ssa + frames + steps;
  if (e.wall_seconds > kLongRunSeconds) {
    e.notes.push_back("this run will take about " + duration_text(e.wall_seconds) +
                      " of wall time on a 2-core machine (estimate); `sadr run --stop-at T` "
                      "runs part of it and `sadr summary` shows where the time goes");
  }
}

}  // namespace

WorkEstimate estimate_work(const Scene& s, const Plan& plan, const MachineLimits& machine,
                           int realizations, int jobs, const FluidSubsteps* fluid) {
  WorkEstimate e;
  const double r = std::max(1, realizations), j = std::max(1, jobs);
  const int d = s.box.dimension;
  e.particles = static_cast<double>(s.particles.size());
  e.sadr_bytes = orchestrator_memory(s.fluid.backend).at(e.particles) * j;
  if (plan.fluid_service) e.fluid_bytes = fluid_memory(s.fluid.backend, d).at(e.particles) * j;
  if (plan.ssa_service) e.ssa_bytes = ssa_memory(d).at(e.particles) * j;
  const double tau = s.time.coupling_step;
  e.step_control = plan.step_control;
  e.coupling_steps =
      std::ceil(s.time.end / tau * (1.0 - 1e-12)) + static_cast<double>(s.output.times.size());
  if (plan.fluid_stepping && fluid && fluid->known()) {
    // Each call of tau / calls takes ceil(length / max_substep) sub-steps (the backends' rules,
    // fluid_service/core stability.hpp), from the limits at t = 0.
    const double calls = std::max(1, plan.fluid_calls_per_step), dt = fluid->max_substep;
    e.substeps_per_step = std::isfinite(dt)
                              ? calls * std::max(1.0, std::ceil(tau / calls / dt * (1.0 - 1e-12)))
                              : calls;
    // In all: each of the n calls takes ceil(length / dt) sub-steps, about end / dt plus half a
    // sub-step of rounding per call (the coupling steps shortened at frames included).
    const double n_calls = calls * e.coupling_steps;
    e.fluid_substeps =
        std::isfinite(dt) ? std::max(n_calls, s.time.end / dt + 0.5 * n_calls) : n_calls;
    e.substep_limit = fluid->criterion();
    e.stable_time_step = fluid->stable_time_step;
    e.limiting_criterion = fluid->limiting_criterion;
  } else if (plan.fluid_stepping) {
    e.substeps_unknown = true;
  }
  e.frames = static_cast<double>(s.output.times.size());
  e.output_bytes = e.frames * frame_bytes(s, e.particles) * r;
  if (plan.ssa_service) {
    e.event_rate = ssa_event_rate(s, e.molecules);
    e.events = e.event_rate * s.time.end * r;
  }

  estimate_time(s, plan, e, r, j);

  const std::string where = " (estimate; docs/cli.md \"Work and memory estimate\")";
  if (e.memory_bytes() > machine.memory_bytes) {
    e.hard.push_back("memory " + bytes_text(e.memory_bytes()) + " is more than the " +
                     machine.memory_source + " " + bytes_text(machine.memory_bytes));
  } else if (e.memory_bytes() > kSoftMemoryShare * machine.memory_bytes) {
    e.soft.push_back("memory " + bytes_text(e.memory_bytes()) + " is more than half the " +
                     machine.memory_source + " " + bytes_text(machine.memory_bytes));
  }
  const double largest = std::max({e.sadr_bytes, e.fluid_bytes, e.ssa_bytes}) / j;
  if (largest > machine.process_bytes) {
    e.hard.push_back("one process needs " + bytes_text(largest) + ", more than RLIMIT_AS " +
                     bytes_text(machine.process_bytes) + " (ulimit -v)");
  }
  if (e.output_bytes > machine.free_disk_bytes) {
    e.hard.push_back("output " + bytes_text(e.output_bytes) + " is more than the free disk " +
                     bytes_text(machine.free_disk_bytes));
  } else if (e.output_bytes > kSoftOutputBytes) {
    e.soft.push_back("output " + bytes_text(e.output_bytes) + " (above " +
                     bytes_text(kSoftOutputBytes) + ")");
  }
  if (e.coupling_steps > kExactIntegerLimit) {
    e.hard.push_back(num(e.coupling_steps) +
                     " coupling steps: beyond 2^53, where step counters stop being exact");
  } else if (e.coupling_steps > kSoftCouplingSteps) {
    e.soft.push_back(num(e.coupling_steps) + " coupling steps (above " + num(kSoftCouplingSteps) +
                     ")");
  }
  const double particle_substeps = e.particles * e.substeps_per_step * e.coupling_steps * r;
  if (particle_substeps > kSoftParticleSubsteps) {
    e.soft.push_back(num(particle_substeps) + " particle sub-steps of the fluid (above " +
                     num(kSoftParticleSubsteps) + ")");
  }
  if (e.frames > kSoftFrames) {
    e.soft.push_back(num(e.frames) + " frames (above " + num(kSoftFrames) + ")");
  }
  if (e.molecules > kExactIntegerLimit) {
    e.hard.push_back(num(e.molecules) + " molecules: beyond 2^53, the exact integer range");
  }
  if (e.events > kSoftEvents) {
    e.soft.push_back(num(e.events) + " SSA events (above " + num(kSoftEvents) + ")");
  }
  for (auto& line : e.hard) line += where;
  for (auto& line : e.soft) line += where;
  return e;
}

double in_process_init_bytes(const WorkEstimate& e, int jobs) {
  return (e.sadr_bytes + kInProcessInitFluidShare * e.fluid_bytes) / std::max(1, jobs);
}

bool in_process_init_fits(double bytes, const MachineLimits& machine) {
  return bytes <= kSoftMemoryShare * machine.memory_bytes && bytes <= machine.process_bytes;
}

std::vector<std::string> WorkEstimate::lines() const {
  std::vector<std::string> out;
  out.push_back("estimate: " + num(particles) + " particles, peak memory " +
                bytes_text(memory_bytes()) + " (sadr " + bytes_text(sadr_bytes) + ", fluid " +
                bytes_text(fluid_bytes) + ", ssa " + bytes_text(ssa_bytes) + ")");
  std::string fluid;
  if (substeps_per_step > 0) {
    fluid = ", ~" + num(substeps_per_step) + " fluid sub-step(s) each (" + substep_limit +
            "; the backend at t = 0: stable time step " + num(stable_time_step) + ", " +
            limiting_criterion + ")";
  } else if (substeps_skipped > 0) {
    fluid =
        ", fluid sub-steps not computed (initialising the backend in sadr for its t = 0 "
        "figure would take ~" +
        bytes_text(substeps_skipped) + ": above half the machine's memory or the process limit)";
  } else if (substeps_unknown) {
    fluid = ", fluid sub-steps not known (the backend did not report its limits)";
  }
  out.push_back(
      "estimate: " + num(coupling_steps) + " coupling steps" +
      (step_control ? " (of the first step; time.tolerance takes as many as it needs)" : "") +
      fluid + "; " + num(frames) + " frame(s), " + bytes_text(output_bytes) + " of output");
  if (event_rate > 0 || molecules > 0) {
    out.push_back("estimate: " + num(molecules) + " molecules, ~" + num(event_rate) +
                  " SSA events per unit time at t = 0, ~" + num(events) + " events in all");
  }
  if (wall_seconds > 0) {
    std::string parts;
    for (const auto& [name, seconds] : time_parts) {
      if (seconds < 0.05 * wall_seconds) continue;
      parts += (parts.empty() ? "" : ", ") + name + " " + duration_text(seconds);
    }
    out.push_back("estimate: about " + duration_text(wall_seconds) +
                  " of wall time on a 2-core machine (" + parts +
                  "; calibrated costs, docs/cli.md)");
  } else {
    out.push_back("estimate: wall time not estimated (the fluid's sub-steps are not known)");
  }
  return out;
}

nlohmann::json WorkEstimate::to_json() const {
  return {{"particles", particles},
          {"sadr_bytes", sadr_bytes},
          {"fluid_bytes", fluid_bytes},
          {"ssa_bytes", ssa_bytes},
          {"coupling_steps", coupling_steps},
          {"substeps_per_step", substeps_per_step},
          {"substep_limit", substep_limit},
          {"stable_time_step", stable_time_step},
          {"limiting_criterion", limiting_criterion},
          {"frames", frames},
          {"output_bytes", output_bytes},
          {"molecules", molecules},
          {"event_rate", event_rate},
          {"events", events},
          {"wall_seconds", wall_seconds},
          {"hard", hard},
          {"soft", soft}};
}

void enforce_limits(const WorkEstimate& e, bool allow_large) {
  if (e.hard.empty() && (allow_large || e.soft.empty())) return;
  std::string msg = "the scene is refused by its work estimate:";
  for (const auto& l : e.hard) msg += "\n  - " + l;
  if (!allow_large) {
    for (const auto& l : e.soft) msg += "\n  - " + l + " [--allow-large lifts this]";
  }
  for (const auto& l : e.lines()) msg += "\n  " + l;
  throw InvalidArgument(msg);
}

}  // namespace sadr::orchestrator
