// SPDX-License-Identifier: MIT
// `sadr summary DIR` (run_summary.hpp), also printed at the end of `sadr run`
// / `sadr resume` (not with -q).
#include <cstdio>
#include <filesystem>
#include <memory>

#include "cli.hpp"
#include "commands.hpp"
#include "sadr/common/log.hpp"
#include "sadr/orchestrator/run_summary.hpp"

namespace sadr::orchestrator {
namespace fs = std::filesystem;

void summarize_at_end(const fs::path& dir, bool quiet) {
  if (quiet) return;
  try {
    print_summary(dir, stderr);
  } catch (const std::exception& e) {
    log::warn("no summary of ", dir.string(), ": ", e.what());
  }
}

Subcommand add_summary_command(CLI::App& app) {
  auto directory = std::make_shared<std::string>();
  auto* summary = app.add_subcommand(
      "summary",
      "what a run or ensemble did: species totals at the first and last frame, wall time per "
      "stage, steps, sub-steps, events, outputs (also printed at the end of run/resume unless -q)");
  summary->add_option("directory", *directory, "the output directory of a run or an ensemble")
      ->required()
      ->check(CLI::ExistingDirectory);

  return {summary, [directory] {
            print_summary(*directory, stdout);
            return static_cast<int>(kExitOk);
          }};
}

}  // namespace sadr::orchestrator
