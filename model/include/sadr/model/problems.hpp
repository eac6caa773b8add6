// SPDX-License-Identifier: MIT
/// \file problems.hpp
/// What a model check finds: each problem names the field, the value and what is allowed.
/// The checks collect every problem; their callers decide how to report them (the scene loader
/// with file:line, a service as one InvalidArgument).
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace sadr::model {

/// One violated rule. `field` is a path relative to the checked object ("rate",
/// "reactants[0].count"); a caller that owns a longer path prefixes it.
struct Problem {
  std::string field;
  std::string value;    ///< as text; "" when the problem is about a combination of fields
  std::string allowed;  ///< what the field accepts, or what is wrong with the combination
  /// "field = value (allowed: allowed)", or "field: allowed" when `value` is empty.
  [[nodiscard]] std::string message() const;
  bool operator==(const Problem&) const = default;
};

/// Collects problems under a path prefix.
class Problems {
 public:
  /// Records {prefix + field, value, allowed}.
  void add(std::string_view field, std::string value, std::string allowed);
  void add(std::string_view field, double value, std::string allowed);
  /// A rule about several fields at once (no single value).
  void add_text(std::string_view field, std::string message);
  /// Range helpers: record a problem unless `value` is finite and >= 0 (> 0).
  void finite_nonneg(std::string_view field, double value);
  void finite_positive(std::string_view field, double value);

  /// Problems recorded from now on are prefixed by `prefix` ("reactions[2]" + "." + field).
  void set_prefix(std::string prefix) { prefix_ = std::move(prefix); }

  [[nodiscard]] bool empty() const { return list_.empty(); }
  [[nodiscard]] const std::vector<Problem>& list() const { return list_; }
  /// Every message joined by "; ".
  [[nodiscard]] std::string text() const;
  /// Throws sadr::InvalidArgument with text() (prefixed by `context` and ": " if given) and one
  /// {field, value} detail per problem, unless there is none.
  void throw_if_any(std::string_view context = {}) const;

 private:
  [[nodiscard]] std::string path(std::string_view field) const;
  std::string prefix_;
  std::vector<Problem> list_;
};

}  // namespace sadr::model
