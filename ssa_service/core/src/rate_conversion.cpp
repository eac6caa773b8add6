// SPDX-License-Identifier: MIT
#include "sadr/ssa/rate_conversion.hpp"

#include <string>

#include "sadr/common/status.hpp"

namespace sadr::ssa {

double mass_action_constant(double k, int order, double volume) {
  switch (order) {
    case 0:
      return k * volume;
    case 1:
      return k;
    case 2:
      return k / volume;
    default:
      throw InvalidArgument("reaction order = " + std::to_string(order) + " (allowed: 0, 1, 2)");
  }
}

}  // namespace sadr::ssa
