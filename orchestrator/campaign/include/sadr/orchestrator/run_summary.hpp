// SPDX-License-Identifier: MIT
/// \file run_summary.hpp
/// `sadr summary DIR` (also printed at the end of `sadr run` / `sadr resume`):
/// what a run did, from its run.json and its first and last CSV frames, and
/// the health of the run from its CSV frames (run_health.hpp). For an ensemble
/// directory: the realizations' manifests summed and the species totals of
/// the ensemble mean (ensemble/frame_*.csv).
#pragma once

#include <cstdio>
#include <filesystem>

namespace sadr::orchestrator {

/// Prints the summary of the run or ensemble in `dir` to `out`.
/// @throws InvalidArgument when `dir` is neither a run nor an ensemble
void print_summary(const std::filesystem::path& dir, std::FILE* out);

}  // namespace sadr::orchestrator
