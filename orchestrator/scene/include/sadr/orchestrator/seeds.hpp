// SPDX-License-Identifier: MIT
/// \file seeds.hpp
/// Seeds of the independent realizations of one scene.
#pragma once

#include <cstdint>

#include "sadr/common/rng.hpp"

namespace sadr::orchestrator {

/// Seed of realization `index` (0-based) of a scene whose `seed` key is
/// `scene_seed`: rng::mix_seed(scene_seed, index). Deterministic and platform
/// independent; realization 0 of a single run uses the same derived seed as
/// realization 0 of an ensemble, so the two agree. Each service then derives
/// its own streams from this seed.
constexpr std::uint64_t realization_seed(std::uint64_t scene_seed, std::uint64_t index) {
  return rng::mix_seed(scene_seed, index);
}

}  // namespace sadr::orchestrator
