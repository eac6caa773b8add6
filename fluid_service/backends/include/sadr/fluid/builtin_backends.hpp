// SPDX-License-Identifier: MIT
/// \file builtin_backends.hpp
/// The one greppable list of the fluid backends that ship with sadr.
#pragma once

#include "sadr/fluid/backend_registry.hpp"

namespace sadr::fluid {

/// Registers "prescribed", "sdpd", "static" and "tdpd" (registry.cpp). New backends add one line
/// there.
void register_builtin_backends(BackendRegistry& registry);

}  // namespace sadr::fluid
