// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/plan.hpp"

#include <algorithm>

#include "sadr/fluid/backend_schema.hpp"
#include "sadr/orchestrator/diagnostics.hpp"
#include "sadr/orchestrator/splitting.hpp"
#include "sadr/orchestrator/step_control.hpp"

namespace sadr::orchestrator {

namespace {
std::string join(const std::vector<std::string>& v) {
  if (v.empty()) return "(none)";
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + v[i];
  return s;
}
}  // namespace

Plan make_plan(const Scene& scene) {
  Plan p;
  p.chosen = scene.chosen;
  // What the backend does, from its schema entry (no backend name is spelled here; the scene
  // loader refused unknown names, a hand-made Scene with one is taken as moving particles).
  const auto* backend = sadr::fluid::schema::find(scene.fluid.backend);
  const bool moving = !backend || backend->capabilities.moves_particles;
  const std::string who = "backend '" + scene.fluid.backend + "'";
  std::vector<std::string> deterministic;
  for (const auto& sp : scene.species) {
    if (sp.stochastic) {
      p.ssa_species.push_back(sp.name);
    } else {
      deterministic.push_back(sp.name);
    }
  }
  for (const auto& rx : scene.reactions) (rx.stochastic ? p.ssa_reactions : p.fluid_reactions)++;
  // Hybrid reactions: which species cross which way (in the scene's species order).
  std::vector<std::string> fluid_reads;
  for (const auto& sp : scene.species) {
    const auto reads = [&](bool stochastic_reaction) {
      return std::any_of(scene.reactions.begin(), scene.reactions.end(), [&](const Reaction& rx) {
        return rx.stochastic == stochastic_reaction &&
               std::find(rx.reads_other.begin(), rx.reads_other.end(), sp.name) !=
                   rx.reads_other.end();
      });
    };
    if (!sp.stochastic && reads(true)) p.frozen_species.push_back(sp.name);
    if (sp.stochastic && reads(false)) fluid_reads.push_back(sp.name);
  }
  p.ssa_time_laws = std::any_of(scene.reactions.begin(), scene.reactions.end(),
                                [](const Reaction& rx) { return rx.stochastic && rx.uses_time; });

  p.ssa_service = !p.ssa_species.empty();
  if (p.ssa_service && scene.ssa.method == model::SsaMethod::kAdaptive) {
    p.ssa_adaptive_tolerance = scene.ssa.tolerance;
  }
  if (!p.ssa_service) p.skipped.push_back("ssa_service: not launched (no stochastic species)");

  p.fluid_stepping = moving || !deterministic.empty();
  p.fluid_service = p.fluid_stepping;
  if (!moving && deterministic.empty()) {
    p.skipped.push_back("fluid_service: not launched (" + who +
                        " moves no particles and there are no deterministic species; particles "
                        "come from the scene)");
  } else if (!moving) {
    p.skipped.push_back("particle motion: none (" + who +
                        " moves no particles; the fluid only integrates the deterministic "
                        "species)");
  }
  p.graph_rebuild_each_step = p.ssa_service && moving;
  p.particles_to_ssa_each_step = p.graph_rebuild_each_step;
  if (p.ssa_service && !moving) {
    p.skipped.push_back("ssa graph rebuild: built once (particles do not move)");
  }
  p.thermal_noise = moving && scene.fluid.temperature > 0.0;
  if (moving && !p.thermal_noise) {
    p.skipped.push_back("thermal noise: none (k_B T = 0: no random numbers in the fluid)");
  }
  if (const auto& b = scene.fluid.boussinesq; b && p.ssa_service && moving) {
    if (std::find(p.ssa_species.begin(), p.ssa_species.end(), b->species) != p.ssa_species.end()) {
      p.back_transfer = true;
      p.back_transfer_species.push_back(b->species);
    }
  }
  for (const auto& s : fluid_reads) {
    if (std::find(p.back_transfer_species.begin(), p.back_transfer_species.end(), s) ==
        p.back_transfer_species.end()) {
      p.back_transfer_species.push_back(s);
    }
    p.back_transfer = p.ssa_service;
  }
  if (p.ssa_service && !p.back_transfer) {
    p.skipped.push_back(
        "back-transfer ssa -> fluid: none (no fluid term depends on a "
        "stochastic species)");
  }
  if (p.fluid_service) {
    p.fluid_species = deterministic;
    for (const auto& s : p.back_transfer_species) p.fluid_species.push_back(s);
  }
  p.fluid_backend = scene.fluid.backend;
  p.splitting = scene.time.splitting;
  if (p.fluid_stepping && p.ssa_service) {
    p.fluid_calls_per_step = p.splitting == Splitting::kStrang ? 2 : 1;
  } else {
    p.fluid_calls_per_step = p.fluid_stepping ? 1 : 0;
    if (p.splitting == Splitting::kStrang) {
      p.skipped.push_back("strang splitting: not needed (only one operator runs)");
    }
  }
  const auto reset_between_calls = [&] {
    return std::any_of(scene.species.begin(), scene.species.end(), [](const Species& sp) {
      return sp.stochastic &&
             std::any_of(sp.boundaries.begin(), sp.boundaries.end(), [](const SpeciesBoundary& b) {
               return b.condition == BoundaryCondition::kInflow;
             });
    });
  };
  p.frame_to_frame =
      p.ssa_service && !p.fluid_service && !reset_between_calls() && !p.ssa_time_laws;
  if (p.frame_to_frame) {
    p.skipped.push_back("coupling step (" + format_number(scene.time.coupling_step) +
                        "): nothing moves; SSA advances frame to frame (to each output, "
                        "checkpoint and stop time in one call, at most " +
                        format_number(kFrameToFrameMaxSteps) + " coupling steps long)");
  }
  if (const auto& tol = scene.time.tolerance) {
    p.step_control = p.ssa_service && p.fluid_stepping;
    p.tolerance = *tol;
    p.first_step = scene.time.coupling_step;
    if (!p.step_control) {
      p.skipped.push_back(
          "error control (time.tolerance): not needed (only one operator runs, "
          "no splitting error); every step is the coupling step");
    }
  }
  if (!p.ssa_service || !p.fluid_stepping) {
    p.overlap_reason = "only one operator runs";
  } else if (p.step_control) {
    p.overlap_reason = "time.tolerance (a rejected step is redone by both services)";
  } else if (p.splitting != Splitting::kLie) {
    p.overlap_reason = "strang splitting (the fluid's second half step needs the SSA's result)";
  } else if (p.back_transfer) {
    p.overlap_reason = "back-transfer (the fluid step reads the SSA's copy numbers)";
  } else {
    p.overlap_allowed = true;
    p.overlap_reason = "not decided";
  }
  // Flow replay: the fluid must not depend on anything that differs between realizations.
  if (!p.ssa_service) {
    p.flow_replay_reason = "no stochastic species: the realizations are all the same";
  } else if (!p.fluid_stepping) {
    p.flow_replay_reason = "the fluid does not step";
  } else if (p.thermal_noise) {
    p.flow_replay_reason = "thermal noise on: k_B T > 0, the fluid draws random numbers";
  } else if (p.back_transfer) {
    p.flow_replay_reason =
        "back-transfer ssa -> fluid: the fluid reads " + join(p.back_transfer_species);
  } else if (p.step_control) {
    p.flow_replay_reason = "time.tolerance: the steps follow the realization";
  } else if (!scene.fluid.body_forces.empty()) {
    p.flow_replay_reason = "fluid.body_forces: every realization writes its forces on bodies";
  } else {
    p.flow_replay_allowed = true;
    p.flow_replay_reason =
        "on only where runs share the fluid: sadr run -r R (R > 1), array tasks, sweeps";
  }
  return p;
}

void decide_flow_replay(Plan& p, bool refused, int realizations) {
  p.flow_replay = false;
  if (!p.flow_replay_allowed) return;  // the reason from make_plan stays
  if (refused) {
    p.flow_replay_reason = "--no-flow-replay";
  } else if (realizations < 2) {
    p.flow_replay_reason = "one realization";
  } else {
    p.flow_replay = true;
    p.flow_replay_reason =
        "the fluid is the same in every realization: computed once, its coupling data "
        "replayed to each";
  }
}

void decide_overlap(Plan& p, OverlapRequest request, unsigned hardware_threads, int fluid_threads,
                    int jobs) {
  p.overlap = false;
  if (!p.overlap_allowed) return;  // the reason from make_plan stays
  if (request == OverlapRequest::kOff) {
    p.overlap_reason = "--no-overlap";
    return;
  }
  if (request == OverlapRequest::kOn) {
    p.overlap = true;
    p.overlap_reason = "--overlap";
    return;
  }
  const unsigned per_job = hardware_threads / static_cast<unsigned>(std::max(1, jobs));
  const std::string counts = std::to_string(per_job) + " hardware thread(s) per realization, " +
                             std::to_string(std::max(1, fluid_threads)) + " fluid thread(s)";
  if (per_job >= 2) {
    p.overlap = true;
    p.overlap_reason = "auto: a second hardware thread for the SSA (" + counts + ")";
  } else {
    p.overlap_reason =
        "auto: no second hardware thread for the SSA (" + counts + "; --overlap forces it)";
  }
}

std::vector<std::string> Plan::lines() const {
  std::vector<std::string> out;
  out.push_back(std::string("fluid_service (") + fluid_backend + "): " +
                (fluid_service
                     ? (fluid_stepping ? "launched, advanced every coupling step" : "launched")
                     : "not launched") +
                (fluid_service ? "; species on the wire: " + join(fluid_species) +
                                     "; reactions: " + std::to_string(fluid_reactions)
                               : ""));
  out.push_back(std::string("ssa_service: ") +
                (ssa_service ? "launched; species on the wire: " + join(ssa_species) +
                                   "; reactions: " + std::to_string(ssa_reactions) +
                                   (graph_rebuild_each_step ? "; graph rebuilt every step"
                                                            : "; graph built once")
                             : "not launched"));
  out.push_back("splitting: " + std::string(to_string(splitting)) + ", " +
                std::to_string(fluid_calls_per_step) + " fluid call(s) per coupling step");
  if (step_control) {
    out.push_back("coupling step: error-controlled, tolerance relative " +
                  format_number(tolerance.relative) + ", absolute " +
                  format_number(tolerance.absolute) + " (first step " + format_number(first_step) +
                  ", at most " + format_number(tolerance.max_step) + ", at least " +
                  format_number(first_step * StepController::kMinStepFraction) +
                  "; splitting error of order " + (splitting == Splitting::kStrang ? "2" : "1") +
                  " estimated from the coupling inputs)");
  }
  out.push_back(std::string("thermal noise: ") + (thermal_noise ? "on" : "off"));
  out.push_back("back-transfer ssa -> fluid: " +
                (back_transfer ? join(back_transfer_species) : std::string("off")));
  if (!frozen_species.empty()) {
    out.push_back("hybrid fluid -> ssa: " + join(frozen_species) +
                  " (concentrations after each fluid stage, frozen over the SSA stage)");
  }
  if (ssa_adaptive_tolerance > 0) {
    out.push_back("ssa method: adaptive, tolerance " + format_number(ssa_adaptive_tolerance) +
                  " (diffusion of abundant voxels leaped, the rest exact)");
  }
  if (ssa_time_laws) {
    out.push_back(
        "ssa laws of t: t held at each SSA stage's start (first order in the "
        "coupling step)");
  }
  out.push_back(std::string("overlap ssa step k || fluid step k+1: ") + (overlap ? "on" : "off") +
                " (" + overlap_reason + ")");
  out.push_back(std::string("flow replay: ") + (flow_replay ? "on" : "off") + " (" +
                flow_replay_reason + ")");
  for (const auto& s : chosen) out.push_back("chosen: " + s);
  for (const auto& s : skipped) out.push_back("skipped: " + s);
  return out;
}

nlohmann::json Plan::to_json() const {
  nlohmann::json j{
      {"fluid_backend", fluid_backend},
      {"fluid_service", fluid_service},
      {"fluid_stepping", fluid_stepping},
      {"ssa_service", ssa_service},
      {"graph_rebuild_each_step", graph_rebuild_each_step},
      {"particles_to_ssa_each_step", particles_to_ssa_each_step},
      {"thermal_noise", thermal_noise},
      {"back_transfer", back_transfer},
      {"splitting", std::string(to_string(splitting))},
      {"fluid_calls_per_step", fluid_calls_per_step},
      {"frame_to_frame", frame_to_frame},
      {"fluid_species", fluid_species},
      {"ssa_species", ssa_species},
      {"back_transfer_species", back_transfer_species},

      {"fluid_reactions", fluid_reactions},
      {"ssa_reactions", ssa_reactions},
      {"skipped", skipped},
      {"overlap", overlap},
      {"overlap_reason", overlap_reason},
      {"flow_replay", flow_replay},
      {"flow_replay_reason", flow_replay_reason},
  };
  if (!frozen_species.empty()) j["frozen_species"] = frozen_species;  // hybrid scenes only
  if (ssa_time_laws) j["ssa_time_laws"] = true;
  if (step_control) {  // time.tolerance scenes only
    j["step_control"] = {{"relative", tolerance.relative},
                         {"absolute", tolerance.absolute},
                         {"first_step", first_step},
                         {"max_step", tolerance.max_step},
                         {"min_step", first_step * StepController::kMinStepFraction},
                         {"order", splitting == Splitting::kStrang ? 2 : 1}};
  }
  if (ssa_adaptive_tolerance > 0) {  // adaptive scenes only
    j["ssa_method"] = "adaptive";
    j["ssa_tolerance"] = ssa_adaptive_tolerance;
  }
  if (!chosen.empty()) j["chosen"] = chosen;  // scenes that leave out the sound speed only
  return j;
}

}  // namespace sadr::orchestrator
