// SPDX-License-Identifier: MIT
#include "exponential.hpp"

#include <cmath>

namespace sadr::ssa::detail {

namespace {
// Marsaglia & Tsang (2000), 256 layers for exp(-x): r and the common area V.
constexpr double kR = 7.69711747013104972;
constexpr double kV = 0.0039496598225815571993;

ZigguratTables make_tables() {
  ZigguratTables t{};
  t.x[0] = kV / std::exp(-kR);  // base layer: [0, r] x [0, f(r)] plus the tail, as a box
  t.x[1] = kR;
  for (int i = 1; i < 255; ++i) {
    // Layer i = [0, x_i] x [f(x_i), f(x_{i+1})] has area V.
    t.x[i + 1] = -std::log(kV / t.x[i] + std::exp(-t.x[i]));
  }
  t.x[256] = 0;
  for (int i = 0; i <= 256; ++i) t.f[i] = std::exp(-t.x[i]);
  t.f[0] = 0;  // the base layer starts at height 0
  return t;
}
}  // namespace

const ZigguratTables& ziggurat_tables() {
  static const ZigguratTables t = make_tables();
  return t;
}

double exponential_slow(rng::Xoshiro256& rng, std::uint64_t bits) {
  const ZigguratTables& t = ziggurat_tables();
  for (;;) {
    const unsigned i = static_cast<unsigned>(bits & 0xFFU);
    const double x = static_cast<double>(bits >> 11) * 0x1.0p-53 * t.x[i];
    if (x < t.x[i + 1]) {
      if (x > 0) return x;  // (only x == 0 gets here: redraw)
    } else if (i == 0) {
      return kR - std::log(rng.uniform());  // tail beyond r: r + Exp(1)
    } else {
      // Wedge of layer i between heights f(x_i) and f(x_{i+1}).
      const double y = t.f[i] + rng.uniform() * (t.f[i + 1] - t.f[i]);
      if (y < std::exp(-x)) return x;
    }
    bits = rng.next();
    const unsigned k = static_cast<unsigned>(bits & 0xFFU);
    const double x2 = static_cast<double>(bits >> 11) * 0x1.0p-53 * t.x[k];
    if (x2 < t.x[k + 1] && x2 > 0) return x2;
  }
}

}  // namespace sadr::ssa::detail
