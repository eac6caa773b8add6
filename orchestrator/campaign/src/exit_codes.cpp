// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/exit_codes.hpp"

#include <cstdio>

#include "sadr/common/status.hpp"
#include "sadr/orchestrator/atomic_file.hpp"

namespace sadr::orchestrator {

int exit_code_of(const std::exception& e) {
  if (dynamic_cast<const IoError*>(&e)) return kExitIoFailure;
  if (const auto* err = dynamic_cast<const Error*>(&e)) {
    switch (err->code()) {
      case StatusCode::kInvalidArgument:
      case StatusCode::kNotFound:
      case StatusCode::kFailedPrecondition:
        return kExitInvalidInput;
      case StatusCode::kNumericalFailure:
      case StatusCode::kOutOfRange:
        return kExitNumericalFailure;
      case StatusCode::kAborted:
        return kExitInterrupted;
      default:
        return kExitServiceFailure;
    }
  }
  return kExitServiceFailure;
}

int report_failure(const std::exception& e) {
  std::fprintf(stderr, "sadr: error: %s\n", e.what());
  return exit_code_of(e);
}

}  // namespace sadr::orchestrator
