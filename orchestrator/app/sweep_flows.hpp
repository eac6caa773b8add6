// SPDX-License-Identifier: MIT
/// \file sweep_flows.hpp
/// (private) Flow replay in a sweep (docs/sweeps.md): the driver keys each
/// point's fluid (fluid_key()) and lets the points whose fluid is shared by at
/// least two runs replay it; each sweep-task then takes the file
/// SWEEP_DIR/flows/<key>.bin, recording it first when it is the first run
/// there (shared_flow_tape()).
#pragma once

#include <filesystem>
#include <string>

#include "commands.hpp"
#include "sadr/orchestrator/sweep_manifest.hpp"

namespace sadr::orchestrator {

/// Decides flow replay for every point of `m` into m.flows (`refused`: --no-flow-replay).
/// Loads each point's scene.
void decide_sweep_flows(SweepManifest& m, bool refused);

/// "flow replay: on (...)" or "flow replay: off (...)" of one point.
std::string flow_line(const PointFlow& flow);

/// Sets plan.flow_replay and its reason for run `run` of `m`: on when its point replays and
/// it starts afresh, or when its checkpoint replays the flow (a run that stepped its fluid
/// goes on stepping it). `resumed`: it continues from the checkpoint in `run_dir`.
void decide_sweep_task_flow(Plan& plan, const SweepManifest& m, const SweepRun& run,
                            const std::filesystem::path& run_dir, bool resumed);

/// keep: aggregates: removes the flow replay files (and their locks) whose runs all
/// finished. @return the files removed
std::size_t remove_finished_flows(const SweepManifest& m, const std::filesystem::path& dir);

}  // namespace sadr::orchestrator
