// SPDX-License-Identifier: MIT
/// \file scene_loader.hpp
/// Reads and validates a scene file (YAML; docs/scene-format.md).
#pragma once

#include <filesystem>
#include <string_view>

#include "sadr/orchestrator/scene.hpp"

namespace sadr::orchestrator {

/// Loads, validates and resolves the scene in `path` (particles generated or
/// read from the CSV file it names, regions resolved to particle indices,
/// initial values and output times computed).
/// @throws sadr::InvalidArgument listing every problem found, one per line,
///   each as "file:line:column: field.path: value ...; allowed: ...".
Scene load_scene(const std::filesystem::path& path);

/// Same as load_scene() for YAML text held in memory.
/// @param text the YAML document
/// @param source_name the name used in messages and to resolve relative
///   paths (particle CSV files are looked up relative to its directory)
Scene parse_scene(std::string_view text, const std::filesystem::path& source_name);

}  // namespace sadr::orchestrator
