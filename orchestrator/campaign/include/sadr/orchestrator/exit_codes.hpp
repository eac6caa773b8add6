// SPDX-License-Identifier: MIT
/// \file exit_codes.hpp
/// Exit codes of the `sadr` CLI (docs/scene-format.md, README.md) and the
/// mapping of an exception to one.
#pragma once

#include <exception>

namespace sadr::orchestrator {

enum ExitCode : int {
  kExitOk = 0,
  kExitInvalidInput = 1,
  kExitUsage = 2,
  kExitServiceFailure = 3,
  kExitNumericalFailure = 4,
  kExitIoFailure = 5,
  kExitInterrupted = 130,
};

/// The exit code of an exception (see ExitCode), without printing.
[[nodiscard]] int exit_code_of(const std::exception& e);
/// Prints the exception ("sadr: error: ...") and returns exit_code_of(e).
int report_failure(const std::exception& e);

}  // namespace sadr::orchestrator
