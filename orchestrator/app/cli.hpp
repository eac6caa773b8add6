// SPDX-License-Identifier: MIT
/// \file cli.hpp
/// (private) What the subcommands' parsers share: a subcommand registers its
/// options (into its own options struct) on the `sadr` app and returns what
/// to run when it is the one given; main() only dispatches.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <vector>

namespace sadr::orchestrator {

struct Subcommand {
  CLI::App* cmd = nullptr;
  std::function<int()> run;  ///< after parsing; exceptions are main()'s to report
};

/// A finite number in [lo, hi], with a short message (CLI11's own ranges print
/// the limits of double with 300 digits).
CLI::Validator finite_range(double lo, double hi, const std::string& what);
/// --set PATH=VALUE (repeatable) into `overrides`.
void add_set_option(CLI::App* cmd, std::vector<std::string>& overrides);
/// --log-level (and -q, which lowers the default "info" to "warn").
void apply_log_level(bool quiet, std::string level);

// The subcommands, in the order of `sadr --help` (one file each).
Subcommand add_validate_command(CLI::App& app);
Subcommand add_run_command(CLI::App& app);
Subcommand add_resume_command(CLI::App& app);
Subcommand add_ensemble_command(CLI::App& app);
Subcommand add_sweep_command(CLI::App& app);
Subcommand add_sweep_task_command(CLI::App& app);
Subcommand add_summary_command(CLI::App& app);
Subcommand add_keygen_command(CLI::App& app);
Subcommand add_backends_command(CLI::App& app);
Subcommand add_graph_command(CLI::App& app);
Subcommand add_geometry_command(CLI::App& app);

}  // namespace sadr::orchestrator
