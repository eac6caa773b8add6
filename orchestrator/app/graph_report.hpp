// SPDX-License-Identifier: MIT
/// \file graph_report.hpp
/// The SSA graph diagnostics of a scene for the plan, and `sadr graph`
/// (graph_command.cpp; the diagnostics are sadr/ssa/graph_diagnostics.hpp).
#pragma once

#include <string>
#include <vector>

#include "commands.hpp"
#include "sadr/orchestrator/plan.hpp"
#include "sadr/orchestrator/scene.hpp"

namespace sadr::orchestrator {

struct GraphReport {
  std::vector<std::string> lines;  ///< for the plan (empty without ssa_service)
  std::string warning;             ///< isolated fluid voxels ("" if none)
};

/// Builds the SSA graph of the scene's initial particles as ssa_service will
/// and diagnoses it (skipped above 2e6 particles: a line says so).
GraphReport graph_report(const Scene& scene, const Plan& plan);

/// `sadr graph SCENE [--format json|csv] [-o FILE]`: the graph's edges with
/// D_ij and each species' rate; the diagnostics go to stderr.
int cmd_graph(const CliOptions& options, const std::string& format);

}  // namespace sadr::orchestrator
