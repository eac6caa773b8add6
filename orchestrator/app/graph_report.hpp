// SPDX-License-Identifier: MIT
/// \file graph_report.hpp
/// The SSA graph diagnostics of a scene for the plan (graph_command.cpp, also
/// `sadr graph`; the diagnostics are sadr/ssa/graph_diagnostics.hpp).
#pragma once

#include <string>
#include <vector>

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

}  // namespace sadr::orchestrator
