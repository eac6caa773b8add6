// SPDX-License-Identifier: MIT
/// \file builtin_backends.hpp
/// The fluid backends that ship with sadr: the list is SADR_FLUID_BACKENDS in
/// fluid_service/backends/backends.cmake (one entry per folder backends/<name>/).
#pragma once

#include "sadr/fluid/backend_registry.hpp"

namespace sadr::fluid {

/// Registers every backend of SADR_FLUID_BACKENDS, in alphabetical order, by calling its
/// `register_<name>_backend(registry)` (defined in its folder). Generated from registry.cpp.in.
void register_builtin_backends(BackendRegistry& registry);

}  // namespace sadr::fluid
