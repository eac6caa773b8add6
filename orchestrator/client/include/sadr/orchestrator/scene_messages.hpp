// SPDX-License-Identifier: MIT
/// \file scene_messages.hpp
/// Scene -> wire messages: the Init requests of fluid_service and ssa_service.
/// Only what each service needs goes on the wire (Plan::fluid_species,
/// Plan::ssa_species, the regions they reference).
#pragma once

#include <cstdint>
#include <string>

#include "sadr/fluid/v1/fluid_service.pb.h"
#include "sadr/orchestrator/plan.hpp"
#include "sadr/orchestrator/scene.hpp"
#include "sadr/ssa/v1/ssa_service.pb.h"

namespace sadr::orchestrator {

/// @param seed realization seed (realization_seed(scene.seed, r))
/// @throws InvalidArgument for scene features the services do not support yet
fluid::v1::InitRequest make_fluid_init(const Scene& scene, const Plan& plan, std::uint64_t seed);

/// @param particles the particle state the first graph is built from
ssa::v1::InitRequest make_ssa_init(const Scene& scene, const Plan& plan, std::uint64_t seed,
                                   const ParticleState& particles);

/// The scene's meaning as one hash ("fnv1a64:<16 hex>"): both services' Init messages
/// (particles, species, reactions, boundaries, fluid and SSA settings, seed; deterministic
/// serialisation), the assigned species, the time stepping, the output schedule and the name.
/// Two files that load to the same scene have the same hash whatever their layout, comments,
/// key order or path (a scene built in Python equals its YAML); source_hash is the bytes'.
std::string scene_meaning_hash(const Scene& scene, const Plan& plan);

/// The fluid's meaning as one hash ("fnv1a64:<16 hex>"): the fluid_service Init message (its
/// seed left out; laws without their origin, backend files as their bytes' hash), the coupling
/// schedule (coupling step, end, splitting, fluid calls per step, geometry to the SSA each
/// step, the species the SSA reads back) and the output times with the species frames ask the
/// fluid for. Two scenes with the same key make the same fluid calls with the same answers when
/// the fluid draws no random numbers: what the SSA alone receives (its rates, species, seed)
/// does not enter it. The flow replay file's header holds it (flow_tape.hpp).
std::string fluid_key(const Scene& scene, const Plan& plan);

}  // namespace sadr::orchestrator
