// SPDX-License-Identifier: MIT
/// \file sdpd_pair_block.hpp
/// SIMD form of the SDPD pair terms (sdpd_pair_physics.hpp) for one particle i and the neighbours
/// within the support, stored as a compact struct-of-arrays block. The backend gathers the
/// block (scalar: minimum image, cut-off test, per-neighbour loads), this kernel evaluates
/// every pair term lane-wise, and the backend sums the per-pair results in neighbour order
/// (so the result does not depend on the SIMD width or the thread count).
/// Only IEEE-exact operations without FMA contraction are used, and every pair-symmetric
/// factor is formed symmetrically ((P_i/d_i^2 + P_j/d_j^2), 1/(d_i d_j), sqrt(1/d_i) sqrt(1/d_j)),
/// so the forces on i and j of one pair are exact negatives (momentum to round-off).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace sadr::fluid {

/// One particle's pairs (inputs gathered by the caller, outputs written by sdpd_pair_block).
struct SdpdPairBlock {
  // inputs
  std::vector<std::uint32_t> j;          ///< neighbour index
  std::array<std::vector<double>, 3> x;  ///< x_ij (D used)
  std::array<std::vector<double>, 3> v;  ///< v_ij (D used)
  std::vector<double> r2;                ///< |x_ij|^2 (< h^2)
  std::vector<double> pd2_j, inv_nd_j, m_j, vol_j, rho_j, sqrt_inv_nd_j;
  /// per-lane i (sdpd_pair_block_lanes only: pairs of several particles i in one block)
  std::vector<std::uint32_t> i;
  std::vector<double> pd2_i, inv_nd_i, rho_i, sqrt_inv_nd_i;
  // outputs
  std::array<std::vector<double>, 3> force;  ///< pair force on i (pressure + viscous)
  std::vector<double> drho;                  ///< continuity + density diffusion term (always)
  std::vector<double> r, f;                  ///< |x_ij|, F_ij
  std::vector<double> amp, amp_r;            ///< noise: sign sqrt(amp2/2), sqrt(amp2/2)/r

  void reserve(std::size_t n);
  [[nodiscard]] std::size_t bytes() const;
};

struct SdpdPairParams {
  double inv_h = 1, f_coef = 1, sqrt_f_coef = 1;
  bool lucy = true;       ///< Lucy (F ~ (1-q)^2) or Wendland C2 (F ~ (1-q)^3)
  double friction = 0;    ///< c_D eta
  double delta_h_c0 = 0;  ///< Molteni-Colagrossi delta h c0
  double eps_h2 = 0;      ///< 0.01 h^2
  bool noise = false;     ///< fill amp, amp_r
  double noise_amp = 0;   ///< sqrt(2 k_B T c_D eta)
};

/// Per-particle quantities of i.
struct SdpdPairI {
  std::uint32_t i;
  double pd2, inv_nd, rho, sqrt_inv_nd;
};

/// Evaluates the n pairs of `b` (D = 1, 2, 3).
template <int D>
void sdpd_pair_block(const SdpdPairParams& p, const SdpdPairI& pi, std::size_t n, SdpdPairBlock& b);

/// The same with the i quantities per lane (b.i, b.pd2_i, b.inv_nd_i, b.rho_i,
/// b.sqrt_inv_nd_i): the pairs of several particles in one call, bit-identical per pair to
/// sdpd_pair_block (fewer calls and partial vectors when each particle has ~12 pairs, 2D).
template <int D>
void sdpd_pair_block_lanes(const SdpdPairParams& p, std::size_t n, SdpdPairBlock& b);

}  // namespace sadr::fluid
