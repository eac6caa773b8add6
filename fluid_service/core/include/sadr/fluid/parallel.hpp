// SPDX-License-Identifier: MIT
/// \file parallel.hpp
/// Threading policy of the fluid loops: OpenMP `parallel for` over particles, only above
/// kMinParallel particles (below it a parallel region costs more than it saves, and on an
/// oversubscribed machine spinning threads cost milliseconds per region). Results never
/// depend on it: every loop is a per-particle gather with a fixed summation order.
#pragma once

#include <cstdint>

namespace sadr::fluid {

inline constexpr std::int64_t kMinParallel = 1024;

}  // namespace sadr::fluid
