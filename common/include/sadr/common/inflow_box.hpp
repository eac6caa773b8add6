// SPDX-License-Identifier: MIT
/// \file inflow_box.hpp
/// An inflow buffer: an axis-aligned box in which a species is held at a
/// concentration (docs/method.md section 4, docs/scene-format.md). Both
/// numerical cores re-impose it after every step: the SSA as copy numbers
/// round(c V_i) (sadr/ssa/inflow.hpp), the fluid as concentrations.
#pragma once

#include <array>
#include <string>

namespace sadr {

struct InflowBox {
  std::string species;
  std::array<double, 3> lower{};  ///< [length] (+-inf allowed; unused axes unbounded)
  std::array<double, 3> upper{};  ///< [length]
  double concentration = 0.0;     ///< >= 0 [molecules/length^d]
  /// Whether the position x (3 values) lies in the box.
  [[nodiscard]] bool contains(const double* x) const {
    for (int a = 0; a < 3; ++a) {
      if (!(x[a] >= lower[a] && x[a] <= upper[a])) return false;
    }
    return true;
  }
};

}  // namespace sadr
