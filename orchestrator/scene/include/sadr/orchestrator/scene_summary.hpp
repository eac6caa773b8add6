// SPDX-License-Identifier: MIT
/// \file scene_summary.hpp
/// A short human-readable description of a loaded scene (what
/// `orchestrator validate` prints for a valid scene).
#pragma once

#include <string>
#include <vector>

#include "sadr/orchestrator/scene.hpp"

namespace sadr::orchestrator {

/// Lines such as "particles: 17 (15 fluid, 2 wall), dx = 0.0625, h = 0.1125",
/// one per aspect: domain, particles, regions, fluid, species, reactions,
/// time, output.
std::vector<std::string> describe_scene(const Scene& scene);

}  // namespace sadr::orchestrator
