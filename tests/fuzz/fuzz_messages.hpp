// SPDX-License-Identifier: MIT
/// \file fuzz_messages.hpp
/// The Init requests of both services for kSmallScene (with the fluid backend
/// swapped), built once per process the way `sadr` builds them, and the check
/// that a reply's Status is a diagnosed error, not an escaped std:: exception.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "fuzz_support.hpp"
#include "sadr/common/status.hpp"
#include "sadr/common/v1/status.pb.h"
#include "sadr/orchestrator/plan.hpp"
#include "sadr/orchestrator/scene_loader.hpp"
#include "sadr/orchestrator/scene_messages.hpp"

namespace sadr::fuzz {

/// The fluid backends the message targets cover (all take kSmallScene's lattice).
inline constexpr std::string_view kBackends[] = {"static", "sdpd"};

inline std::string small_scene(std::string_view backend) {
  std::string text(kSmallScene);
  if (backend != "static") {
    const std::string from = "{backend: static, h_over_dx: 2.0}";
    text.replace(text.find(from), from.size(),
                 "{backend: " + std::string(backend) +
                     ", h_over_dx: 2.0, sound_speed: 1.0, shear_viscosity: 0.1}");
  }
  return text;
}

struct SmallInits {
  fluid::v1::InitRequest fluid;
  ssa::v1::InitRequest ssa;
};

/// Init requests for kSmallScene with fluid backend kBackends[k % 2].
inline const SmallInits& small_inits(std::size_t k) {
  static const auto make = [](std::string_view backend) {
    const auto scene = orchestrator::parse_scene(small_scene(backend), "fuzz.yaml");
    const auto plan = orchestrator::make_plan(scene);
    return SmallInits{orchestrator::make_fluid_init(scene, plan, 7),
                      orchestrator::make_ssa_init(scene, plan, 7, scene.particles)};
  };
  static const SmallInits inits[] = {make(kBackends[0]), make(kBackends[1])};
  return inits[k % 2];
}

/// A handler turns every exception into the reply's Status; one that is not a
/// sadr::Error (an undiagnosed std:: exception: out_of_range, bad_alloc, ...)
/// becomes INTERNAL "unexpected exception: ...". That is a finding: abort.
inline void require_diagnosed(const common::v1::Status& status, std::string_view what) {
  if (status.code() == static_cast<int>(StatusCode::kInternal) &&
      status.message().rfind("unexpected exception", 0) == 0) {
    std::fprintf(stderr, "fuzz: %.*s: undiagnosed error: %s\n", static_cast<int>(what.size()),
                 what.data(), status.message().c_str());
    std::abort();
  }
  if (status.code() != 0) note_refusal(status.message());
}

}  // namespace sadr::fuzz
