// SPDX-License-Identifier: MIT
/// \file scene_override.hpp
/// Scene overrides (`sadr run SCENE --set PATH=VALUE`, the parameters of a
/// sweep): a dotted path into the scene's YAML tree and a YAML value. They are
/// applied to the tree before the loader reads it, so an overridden value is
/// validated by exactly the code that validates the file, and its errors name
/// the override. Path syntax (docs/cli.md):
///   fluid.sound_speed            a key of a map (added if absent)
///   reactions[annihilation].rate a list item by its `name`
///   species[0].diffusivity       a list item by its 0-based index
///   output.times                 VALUE is YAML: 0.2, [0.1, 0.2], {a: 1}, text
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace sadr::orchestrator {

struct SceneOverride {
  std::string path;   ///< "reactions[annihilation].rate"
  std::string value;  ///< YAML text of the new value, "0.2"
  /// "PATH=VALUE" as the user wrote it (recorded in run.json, named in errors).
  [[nodiscard]] std::string text() const { return path + "=" + value; }
  bool operator==(const SceneOverride&) const = default;
};

/// Splits "PATH=VALUE" at the first '='. Checks the path's syntax (segments
/// `key`, `key[name]`, `key[index]`, separated by '.').
/// @throws sadr::InvalidArgument naming the text and what is wrong.
SceneOverride parse_override(std::string_view text);

/// parse_override() of each text, in order (later ones win on the same path).
std::vector<SceneOverride> parse_overrides(const std::vector<std::string>& texts);

}  // namespace sadr::orchestrator
