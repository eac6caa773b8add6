// SPDX-License-Identifier: MIT
/// \file periodic.hpp
/// THE minimum-image and wrap rules on a periodic axis, shared by both
/// numerical cores (the fluid's PeriodicBox, the SSA's neighbour lists, cell
/// grid and graph builder), so that both see the same pair distances bit for
/// bit.
#pragma once

#include <cmath>

namespace sadr {

/// Minimum image of a coordinate difference dx on a periodic axis of length
/// len, for |dx| < 1.5 len (both points inside the box, or one period off):
/// dx - len if dx > len/2, dx + len if dx < -len/2, else dx. Odd in dx bit for
/// bit, so r_ij == r_ji exactly.
inline double minimum_image(double dx, double len) {
  const double half = 0.5 * len;
  if (dx > half) return dx - len;
  if (dx < -half) return dx + len;
  return dx;
}

/// A coordinate of a periodic axis [lo, hi) wrapped into it, any number of
/// periods away; a result that round-off puts on hi becomes lo.
inline double wrap_into(double v, double lo, double hi) {
  const double len = hi - lo;
  v = lo + (v - lo) - len * std::floor((v - lo) / len);
  return v >= hi ? lo : v;
}

}  // namespace sadr
