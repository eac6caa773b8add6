// SPDX-License-Identifier: MIT
/// \file status.hpp
/// Status codes and the exception types every sadr library throws.
///
/// Inside a process, errors travel as exceptions derived from sadr::Error;
/// at a process boundary the service loop converts them to a Status (code,
/// message, details) that goes on the wire. Exceptions never cross ZeroMQ.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace sadr {

/// Error categories; the numeric values are the wire values of
/// sadr.common.v1.StatusCode (keep both in step).
enum class StatusCode : int {
  kOk = 0,
  kInvalidArgument = 1,  ///< bad input: a field out of range, unknown name, ...
  kFailedPrecondition =
      2,                  ///< the call is not valid in the current state (e.g. advance before init)
  kNotFound = 3,          ///< a named thing does not exist
  kOutOfRange = 4,        ///< a value left its allowed band during the run
  kNumericalFailure = 5,  ///< non-finite values, blow-up, broken stability limit
  kUnavailable = 6,       ///< a peer is unreachable
  kDeadlineExceeded = 7,  ///< a peer did not answer in time
  kProtocolMismatch = 8,  ///< wrong protocol version, service kind or message type
  kInternal = 9,          ///< a bug: an invariant did not hold
  kAborted = 10,          ///< stopped on request (signal, shutdown)
};

/// Human-readable name of a code ("INVALID_ARGUMENT", ...).
std::string_view to_string(StatusCode code);

/// The result of an operation that crosses a process boundary.
struct Status {
  StatusCode code = StatusCode::kOk;
  std::string message;  ///< one sentence saying what went wrong and what was expected
  std::vector<std::pair<std::string, std::string>>
      details;  ///< key/value context (field, value, ...)

  [[nodiscard]] bool ok() const { return code == StatusCode::kOk; }
  /// "CODE: message [k=v, ...]".
  [[nodiscard]] std::string to_string() const;
  static Status Ok() { return {}; }
};

/// Base of all sadr exceptions; carries a StatusCode and optional details.
class Error : public std::runtime_error {
 public:
  Error(StatusCode code, const std::string& message,
        std::vector<std::pair<std::string, std::string>> details = {})
      : std::runtime_error(message), code_(code), details_(std::move(details)) {}
  [[nodiscard]] StatusCode code() const { return code_; }
  [[nodiscard]] const std::vector<std::pair<std::string, std::string>>& details() const {
    return details_;
  }
  [[nodiscard]] Status status() const { return Status{code_, what(), details_}; }

 private:
  StatusCode code_;
  std::vector<std::pair<std::string, std::string>> details_;
};

/// Bad input. The message names the field, the value and the allowed range.
class InvalidArgument : public Error {
 public:
  explicit InvalidArgument(const std::string& message,
                           std::vector<std::pair<std::string, std::string>> details = {})
      : Error(StatusCode::kInvalidArgument, message, std::move(details)) {}
};

/// Non-finite values, blow-up or a broken stability limit.
class NumericalFailure : public Error {
 public:
  explicit NumericalFailure(const std::string& message,
                            std::vector<std::pair<std::string, std::string>> details = {})
      : Error(StatusCode::kNumericalFailure, message, std::move(details)) {}
};

/// A call that is not valid in the current state.
class FailedPrecondition : public Error {
 public:
  explicit FailedPrecondition(const std::string& message)
      : Error(StatusCode::kFailedPrecondition, message) {}
};

/// Converts any exception (sadr::Error or std::exception) into a Status.
Status status_from_exception(const std::exception& e);

/// Throws sadr::Error carrying `status` unless it is OK.
void throw_if_error(const Status& status);

/// Formats a double for error messages with enough digits to be unambiguous.
std::string format_value(double value);

/// Formats a double as a person writes it in a scene or CSV ("%.10g": 0.1, not
/// 0.10000000000000001).
std::string format_short(double value);

}  // namespace sadr
