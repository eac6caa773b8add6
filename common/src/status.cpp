// SPDX-License-Identifier: MIT
#include "sadr/common/status.hpp"

#include <cstdio>
#include <sstream>

namespace sadr {

std::string_view to_string(StatusCode code) {
  switch (code) {
    case StatusCode::kOk:
      return "OK";
    case StatusCode::kInvalidArgument:
      return "INVALID_ARGUMENT";
    case StatusCode::kFailedPrecondition:
      return "FAILED_PRECONDITION";
    case StatusCode::kNotFound:
      return "NOT_FOUND";
    case StatusCode::kOutOfRange:
      return "OUT_OF_RANGE";
    case StatusCode::kNumericalFailure:
      return "NUMERICAL_FAILURE";
    case StatusCode::kUnavailable:
      return "UNAVAILABLE";
    case StatusCode::kDeadlineExceeded:
      return "DEADLINE_EXCEEDED";
    case StatusCode::kProtocolMismatch:
      return "PROTOCOL_MISMATCH";
    case StatusCode::kInternal:
      return "INTERNAL";
    case StatusCode::kAborted:
      return "ABORTED";
  }
  return "UNKNOWN";
}

std::string Status::to_string() const {
  std::ostringstream out;
  out << sadr::to_string(code);
  if (!message.empty()) out << ": " << message;
  if (!details.empty()) {
    out << " [";
    for (std::size_t i = 0; i < details.size(); ++i) {
      if (i) out << ", ";
      out << details[i].first << "=" << details[i].second;
    }
    out << "]";
  }
  return out.str();
}

Status status_from_exception(const std::exception& e) {
  if (const auto* err = dynamic_cast<const Error*>(&e)) return err->status();
  return Status{StatusCode::kInternal, std::string("unexpected exception: ") + e.what(), {}};
}

void throw_if_error(const Status& status) {
  if (!status.ok()) throw Error(status.code, status.message, status.details);
}

std::string format_value(double value) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", value);
  return buf;
}

std::string format_short(double value) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.10g", value);
  return buf;
}

}  // namespace sadr
