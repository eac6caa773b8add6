// SPDX-License-Identifier: MIT
/// \file yaml_reader.hpp
/// (private) Typed access to YAML nodes that records every problem in a
/// Diagnostics with file:line:column, the field path, the value and what is
/// allowed, instead of throwing at the first one.
#pragma once

#include <yaml-cpp/yaml.h>

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sadr/model/problems.hpp"
#include "sadr/orchestrator/diagnostics.hpp"

namespace sadr::orchestrator::detail {

/// Range a number must lie in.
enum class Bound { kAny, kPositive, kNonNegative };

/// A YAML node and its field path ("species[1].initial[0]"); path "" is the root.
struct Field {
  YAML::Node node;
  std::string path;
  SourceLocation where;  ///< of the node, or of its parent when it is absent
};

class YamlReader {
 public:
  explicit YamlReader(Diagnostics& diagnostics) : diag_(diagnostics) {}

  Diagnostics& diag() { return diag_; }
  void error(const Field& f, std::string_view message) { diag_.error(f.where, f.path, message); }
  void warning(const Field& f, std::string_view message) {
    diag_.warning(f.where, f.path, message);
  }

  static SourceLocation location(const YAML::Node& node);
  /// The child `key` of a map field (node undefined when absent).
  static Field child(const Field& parent, std::string_view key);
  /// The i-th element of a sequence field.
  static Field element(const Field& parent, std::size_t i);
  static bool present(const Field& f) { return f.node.IsDefined() && !f.node.IsNull(); }

  /// Checks that `f` is a map whose keys are all in `allowed`; reports unknown
  /// keys (with the nearest valid name) and duplicates. False if not a map.
  bool expect_map(const Field& f, std::span<const std::string_view> allowed);
  /// False (and reported) if `f` is present but not a sequence.
  bool expect_sequence(const Field& f);

  /// The deepest node the file has along `path` below `object` ("reactants[0].count": the
  /// reactants list's first entry's count, or the nearest present ancestor).
  static Field resolve(const Field& object, std::string_view path);
  /// Reports each of the model's problems (model::check on what was read from `object`) at
  /// its field's node: "VALUE is out of range; allowed: ALLOWED [unit]", the unit from
  /// `units` by the problem's field (e.g. {"rate", "1/time"}).
  /// A problem whose field starts with an `aliases` key is reported at that alias's field
  /// instead (a reaction's "reactants" at its "equation" when it has one).
  void report(const Field& object, const model::Problems& problems,
              std::span<const std::pair<std::string_view, std::string_view>> units = {},
              std::span<const std::pair<std::string_view, Field>> aliases = {});

  /// A finite number in `bound`; nullopt when absent (reported if `required`)
  /// or invalid (reported). `unit` is printed in messages, e.g. "length".
  std::optional<double> number(const Field& parent, std::string_view key, Bound bound,
                               std::string_view unit, bool required);
  double number_or(const Field& parent, std::string_view key, double fallback, Bound bound,
                   std::string_view unit);
  /// A whole number in [lo, hi].
  std::optional<std::uint64_t> integer(const Field& parent, std::string_view key, std::uint64_t lo,
                                       std::uint64_t hi, bool required);
  std::optional<std::string> string(const Field& parent, std::string_view key, bool required);
  /// One of `allowed` (reported with the nearest allowed value otherwise).
  std::optional<std::string> choice(const Field& parent, std::string_view key,
                                    std::span<const std::string_view> allowed, bool required,
                                    std::string_view what = "value");
  std::optional<bool> boolean(const Field& parent, std::string_view key, bool required);
  /// `n` numbers as a sequence (unused components 0).
  std::optional<std::array<double, 3>> vector(const Field& parent, std::string_view key, int n,
                                              std::string_view unit, bool required);
  /// A list of strings (a single scalar is accepted as a list of one).
  std::optional<std::vector<std::string>> string_list(const Field& parent, std::string_view key,
                                                      bool required);

  /// Reads a scalar field as a number with the same checks as number().
  std::optional<double> number_at(const Field& f, Bound bound, std::string_view unit);

 private:
  Diagnostics& diag_;
};

std::string allowed_text(Bound bound, std::string_view unit);

}  // namespace sadr::orchestrator::detail
