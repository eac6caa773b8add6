// SPDX-License-Identifier: MIT
/// \file diagnostics.hpp
/// Collects input problems (file:line:column, field path, value, what is
/// allowed) so that one pass over a scene reports all of them at once, and
/// suggests the nearest valid name for a misspelt key or value.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace sadr::orchestrator {

/// A position in a text file; 1-based. line == 0 means "unknown".
struct SourceLocation {
  int line = 0;
  int column = 0;
};

/// Accumulates error messages of the form
/// "file:line:column: field: message" and throws them together.
class Diagnostics {
 public:
  /// @param file name printed in front of every message (the scene path as given).
  explicit Diagnostics(std::string file) : file_(std::move(file)) {}

  /// Records one problem. `field` is a path like "species[1].diffusivity";
  /// empty when the message already names its context.
  /// A `field` at or under an overridden path (add_override) loses its file
  /// position and gets " (set by --set PATH=VALUE)" appended.
  void error(SourceLocation where, std::string_view field, std::string_view message);

  /// Records a warning: the scene is valid but very likely not what was meant (a term that
  /// selects no particle, molecules that can never move). Formatted as error(); kept apart.
  void warning(SourceLocation where, std::string_view field, std::string_view message);
  /// The warnings recorded, sorted by position in the file.
  [[nodiscard]] std::vector<std::string> warnings() const;

  /// Declares that the node at `resolved_path` (as the loader spells it,
  /// "reactions[0].rate") comes from the override `text` (scene_override.hpp).
  void add_override(std::string resolved_path, std::string text);
  /// The text of the override that set `field` or one of its parents ("" if none).
  [[nodiscard]] std::string override_of(std::string_view field) const;

  [[nodiscard]] bool empty() const { return messages_.empty(); }
  [[nodiscard]] std::size_t size() const { return messages_.size(); }
  [[nodiscard]] const std::vector<std::string>& messages() const { return messages_; }
  [[nodiscard]] const std::string& file() const { return file_; }

  /// Throws sadr::InvalidArgument listing every recorded problem, one per
  /// line, sorted by position in the file (problems without a position last),
  /// if there is at least one; returns otherwise.
  void throw_if_any() const;

 private:
  std::string file_;
  std::vector<std::string> messages_;                           ///< in the order recorded
  std::vector<SourceLocation> where_;                           ///< parallel to messages_
  std::vector<std::pair<std::string, std::string>> overrides_;  ///< resolved path, text
  std::vector<std::string> warnings_;
  std::vector<SourceLocation> warning_where_;  ///< parallel to warnings_
  [[nodiscard]] std::string format(SourceLocation& where, std::string_view field,
                                   std::string_view message) const;
};

/// Edit distance (insertions, deletions, substitutions, each cost 1).
std::size_t levenshtein(std::string_view a, std::string_view b);

/// The candidate closest to `word` if it is plausibly a typo of it (edit
/// distance <= max(2, |word| / 3)), or a known synonym (e.g. "kappa" ->
/// "diffusivity", "tau" -> "coupling_step") that is among the candidates.
std::optional<std::string> nearest_name(std::string_view word,
                                        std::span<const std::string_view> candidates);

/// "a, b, c": the candidates joined for an "allowed: ..." message.
std::string join_names(std::span<const std::string_view> names);

/// Shortest decimal text that reads back to the same double ("0.1", "1e-17").
std::string format_number(double value);

}  // namespace sadr::orchestrator
