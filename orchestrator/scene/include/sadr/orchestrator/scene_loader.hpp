// SPDX-License-Identifier: MIT
/// \file scene_loader.hpp
/// Reads and validates a scene file (YAML; docs/scene-format.md).
#pragma once

#include <filesystem>
#include <span>
#include <string_view>

#include "sadr/orchestrator/scene.hpp"
#include "sadr/orchestrator/scene_override.hpp"

namespace sadr::orchestrator {

/// Loads, validates and resolves the scene in `path` (particles generated or
/// read from the CSV file it names, regions resolved to particle indices,
/// initial values and output times computed).
/// @throws sadr::InvalidArgument listing every problem found, one per line,
///   each as "file:line:column: field.path: value ...; allowed: ...".
/// @param overrides applied to the YAML tree before it is read
///   (scene_override.hpp); then Scene::source_hash is the hash of the effective
///   scene (file bytes, each override's text, particle file bytes) and
///   Scene::overrides lists them.
Scene load_scene(const std::filesystem::path& path, std::span<const SceneOverride> overrides = {});

/// Same as load_scene() for YAML text held in memory.
/// @param text the YAML document
/// @param source_name the name used in messages and to resolve relative
///   paths (particle CSV files are looked up relative to its directory)
Scene parse_scene(std::string_view text, const std::filesystem::path& source_name,
                  std::span<const SceneOverride> overrides = {});

}  // namespace sadr::orchestrator
