// SPDX-License-Identifier: MIT
/// \file pair_noise_batch.hpp
/// The random numbers of the thermal pair noise (PairNoise, pair_terms.hpp), generated for a
/// whole neighbour list at once so that Philox and Box-Muller run in SIMD lanes.
///
/// For the pair (lo, hi) = (min(i, j), max(i, j)) at `step` the four 32-bit words
/// b = Philox4x32-10(key = seed, counter = {lo, hi, step, purpose << 24 | step >> 32}) give
/// four independent unit-variance numbers:
///  * kGaussian: two Box-Muller pairs in single precision. Radius sqrt(-2 ln u) with
///    u = (2 (b0 >> 9) + 1) 2^-24 in (0, 1) (24 bits, exact in float; tails cut at 5.8 sigma,
///    probability 7e-9), angle uniform on the circle: quadrant from the two low bits of b1,
///    offset (b1 >> 8) 2^-24 - 1/2 of a quadrant. ln, sin and cos are the Cephes single precision
///    polynomials (relative error ~1e-7), branch-free, so the loop vectorises.
///  * kUniform: 2 sqrt(3) ((b + 1/2) 2^-32 - 1/2), variance 1.
/// Only IEEE-exact operations (+, *, /, sqrt, conversions; no FMA contraction) are used, so the
/// vector lanes and the scalar remainder give bit-identical numbers for the same pair, which
/// keeps the pair forces exact negatives of each other (momentum conserved to round-off).
#pragma once

#include <cstddef>
#include <cstdint>

#include "sadr/fluid/fluid_model.hpp"

namespace sadr::fluid {

/// Writes z0[k], z1[k], z2[k], z3[k] (k < n) for the pairs (i, j[k]).
void pair_noise_numbers(std::uint64_t seed, std::uint64_t step, std::uint32_t i,
                        const std::uint32_t* j, std::size_t n, NoiseDistribution distribution,
                        float* z0, float* z1, float* z2, float* z3);

/// The same numbers for pairs (i[k], j[k]) of several particles i at once: the SDPD half-pair
/// path batches a few particles (2D: ~12 pairs each) so that the 16-lane vectors are full.
void pair_noise_numbers_lanes(std::uint64_t seed, std::uint64_t step, const std::uint32_t* i,
                              const std::uint32_t* j, std::size_t n, NoiseDistribution distribution,
                              float* z0, float* z1, float* z2, float* z3);

}  // namespace sadr::fluid
