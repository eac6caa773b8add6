// SPDX-License-Identifier: MIT
/// \file exponential.hpp
/// Exp(1) variates for the NSM by the ziggurat method (Marsaglia & Tsang 2000),
/// instead of -log(U): one 64-bit draw, one table lookup, one multiply and one
/// compare in ~98.9 % of the calls; log/exp only in the wedges and the tail.
///
/// Exactness: the ziggurat is a rejection method, exact in distribution up to the
/// resolution of the uniforms it uses (as -log(U) is): 256 layers of equal area
/// V; a point uniform in a layer is accepted if it lies under exp(-x) (inside the
/// inner rectangle without evaluating exp; in a wedge with one exp); the base
/// layer's tail beyond r is r + Exp(1) (memorylessness), drawn as r - log(U).
/// Unlike Marsaglia's 32-bit version, the layer index (8 bits) and the position
/// in the layer (53 bits) come from disjoint bits of one 64-bit word, so they
/// are independent. Tested: KS and tail frequency (exponential_test.cpp), and
/// every statistical test of the solver.
#pragma once

#include <cstdint>

#include "sadr/common/rng.hpp"

namespace sadr::ssa::detail {

struct ZigguratTables {
  double x[257];  ///< layer edges: x[0] = V / f(r) (base), x[1] = r, ..., x[256] = 0
  double f[257];  ///< exp(-x[i])
};
/// The tables (computed once, deterministic).
const ZigguratTables& ziggurat_tables();
/// Wedge / tail / retry path of exponential() (rare).
double exponential_slow(rng::Xoshiro256& rng, std::uint64_t bits);

/// One Exp(1) variate, > 0 and finite (a zero is redrawn: the NSM divides by it
/// never, but a zero waiting time would be a measure-zero event anyway).
inline double exponential(rng::Xoshiro256& rng) {
  static const ZigguratTables& t = ziggurat_tables();
  const std::uint64_t bits = rng.next();
  const unsigned i = static_cast<unsigned>(bits & 0xFFU);
  const double x = static_cast<double>(bits >> 11) * 0x1.0p-53 * t.x[i];
  if (x < t.x[i + 1] && x > 0) return x;
  return exponential_slow(rng, bits);
}

}  // namespace sadr::ssa::detail
