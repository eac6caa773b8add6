// SPDX-License-Identifier: MIT
/// \file scene_override_tree.hpp
/// (private) Applies scene overrides to a scene's YAML tree (scene_override.hpp).
#pragma once

#include <yaml-cpp/yaml.h>

#include <span>

#include "sadr/orchestrator/diagnostics.hpp"
#include "sadr/orchestrator/scene_override.hpp"

namespace sadr::orchestrator::detail {

/// Sets each override's value in `root`, in order. Records each resolved path
/// in `diag` (so that messages about it name the override) and reports a path
/// that does not resolve (a missing list item, an index out of range, a
/// scalar where a map or list is needed, a value that is not YAML).
void apply_overrides(YAML::Node& root, std::span<const SceneOverride> overrides, Diagnostics& diag);

}  // namespace sadr::orchestrator::detail
