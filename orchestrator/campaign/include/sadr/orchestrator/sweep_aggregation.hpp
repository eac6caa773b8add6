// SPDX-License-Identifier: MIT
/// \file sweep_aggregation.hpp
/// The end of `sadr sweep`: every point whose runs all finished aggregated
/// (sweep_aggregate.hpp) into SWEEP_DIR/points/pPPPP/, the keep policy
/// applied, SWEEP_DIR/observables.csv rewritten, and the table of the runs
/// that did not finish (docs/sweeps.md).
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

#include "sadr/orchestrator/sweep_manifest.hpp"

namespace sadr::orchestrator {

/// A CSV field: quoted when it holds a comma, a quote or a newline.
[[nodiscard]] std::string csv_field(const std::string& s);

/// Aggregates each point whose runs all finished (and that is not aggregated
/// yet) and records it in m.aggregates ("done", "incomplete", "refused" when
/// its runs ran different scenes, "failed"); applies the keep policy and
/// rewrites DIR/observables.csv. Unless `quiet`, a line per point aggregated.
void aggregate_sweep(SweepManifest& m, const std::filesystem::path& dir, bool quiet);

/// Prints every run that did not finish, with its reason; returns how many.
std::size_t print_sweep_failures(const SweepManifest& m);

}  // namespace sadr::orchestrator
