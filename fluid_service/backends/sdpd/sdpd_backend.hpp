// SPDX-License-Identifier: MIT
/// \file sdpd_backend.hpp
/// Smoothed dissipative particle dynamics (Espanol & Revenga 2003) with deterministic
/// reaction-diffusion (SPEC section 2), integrated with the explicit trapezoidal
/// predictor-corrector of drawert2019 eq 24 on Y = [x, v, rho, C].
///
/// Two pair loops, both bit-identical on any thread count (no atomics): with wall particles,
/// transported species or reactions, sdpd_rates.cpp gathers, for each particle, the
/// evaluators of pair_terms.hpp over its full neighbour list; otherwise (bulk fluid)
/// sdpd_half_pairs.hpp evaluates each pair once and writes both sides, slab colour by slab
/// colour (measured 1.5-2x faster per step on the issue-4 benchmark, docs/fluid-core.md 6). Wall
/// particles (kind kWall) never move, keep v = 0 (no-slip), evolve their density by continuity (so
/// the fluid cannot penetrate) and hold their species values (Dirichlet) or are excluded (no-flux /
/// Neumann ghost).
#pragma once

#include <array>
#include <memory>

#include "sadr/fluid/fluid_backend.hpp"
#include "sadr/fluid/kernel.hpp"
#include "sadr/fluid/neighbor_list.hpp"
#include "sadr/fluid/pair_terms.hpp"
#include "sadr/fluid/sdpd_pair_block.hpp"
#include "sadr/fluid/species_transport.hpp"
#include "sadr/fluid/stability.hpp"
#include "sadr/fluid/tait_eos.hpp"

namespace sadr::fluid {

class SdpdBackend final : public FluidBackend {
 public:
  [[nodiscard]] std::string_view name() const override { return "sdpd"; }
  [[nodiscard]] Capabilities capabilities() const override { return {true, true, true, true}; }
  void initialize(const FluidModel& model, const ParticleState& initial,
                  const std::vector<std::vector<double>>& concentrations) override;
  StepReport advance(std::uint64_t step_index, double time_step) override;
  void read_state(ParticleState& out) const override;
  [[nodiscard]] const std::vector<double>& concentrations(int species) const override;
  void set_concentrations(int species, std::span<const double> values) override;
  [[nodiscard]] std::string save() const override;
  void restore(std::string_view blob) override;
  [[nodiscard]] double time() const override { return time_; }

  /// Rates of change at one state (public for the tests of the pair loop).
  struct Rates {
    std::vector<double> acc;        ///< deterministic acceleration, 3N [length/time^2]
    std::vector<double> acc_noise;  ///< noise acceleration times sqrt(dt), 3N (empty if k_B T = 0)
    std::vector<double> drho;       ///< N [mass/length^d/time]
    std::vector<std::vector<double>> dc;  ///< [species][N] [C/time]
    double max_k_sum = 0;                 ///< max_i sum_j K_ij over fluid i [1/length^2]
    double max_visc_sum = 0;  ///< max_i (a + b)/rho_i sum_j V_j F_ij [1/(length^2)] / viscosity
  };
  /// Evaluates the rates at the current state with the noise of `noise_step` (testing aid).
  void evaluate_current(std::uint64_t noise_step, Rates& out);
  /// Heap bytes held by the backend (state, scratch, neighbour list), for the benchmark.
  [[nodiscard]] std::size_t memory_bytes() const;
  /// Stability limits at the current state (evaluates the rates once).
  [[nodiscard]] StabilityLimits current_limits();
  /// Neighbour-list builds since initialize() (benchmark diagnostics).
  [[nodiscard]] std::uint64_t list_builds() const { return list_builds_; }

 private:
  struct Y {
    std::vector<double> x, v, rho;
    std::vector<std::vector<double>> c;
  };
  void evaluate(Y& y, std::uint64_t noise_step, Rates& out, bool with_noise);
  template <int D>
  void evaluate_dim(Y& y, std::uint64_t noise_step, Rates& out, bool with_noise);
  /// Wall-free, species-free systems: each pair evaluated once (sdpd_half_pairs.hpp).
  template <int D>
  void evaluate_half(const Y& y, std::uint64_t noise_step, Rates& out, bool noise_on,
                     const SdpdPairParams& pp, double c_d);
  template <int D>
  void summation_half(Y& y);
  /// Calls per_slab(first, last, scratch) for the members [first, last) of every slab, slab
  /// phase by slab phase.
  template <class PerSlab>
  void slab_phases(PerSlab&& per_slab);
  void ensure_neighbors(const std::vector<double>& x);
  void rebuild_neighbors(const std::vector<double>& x);  ///< list + slabs at positions x
  StabilityLimits limits(const Y& y, const Rates& r) const;
  void check_health(std::uint64_t step_index, std::uint32_t substep) const;
  void require_initialized(const char* what) const;

  bool initialized_ = false;
  FluidModel model_;
  Kernel kernel_;
  TaitEos eos_;
  PeriodicBox pbox_;
  std::unique_ptr<CellListBuilder> builder_;
  NeighborList nlist_;
  std::vector<double> list_ref_x_;  ///< positions at the last list build (saved: exact restarts)
  std::uint64_t list_builds_ = 0;
  /// Half-pair path (no wall particles, no Morris walls, no transported species, no reactions):
  /// slabs along the last active axis, assigned at each list build (sdpd_half_pairs.hpp).
  static constexpr std::uint32_t kSlabReach = 2;  ///< slab width >= list cutoff / kSlabReach
  bool half_ok_ = false;
  std::uint32_t slab_count_ = 0;
  bool slab_wrap_ = false;                   ///< slab axis periodic
  std::vector<std::uint32_t> slab_of_;       ///< particle -> slab
  std::vector<std::uint32_t> slab_start_;    ///< CSR over slabs (slab_count_ + 1)
  std::vector<std::uint32_t> slab_members_;  ///< particles of each slab, by index
  /// Half path: what a pair reads of particle j, one 64-byte line per particle (the gather of a
  /// neighbour touches one line instead of seven arrays; 2D 1e5 streams through L3), and what it
  /// adds to j (force, noise impulse, continuity, sum_j F_ij/d_j for the viscous limit).
  struct alignas(64) HalfIn {
    double v[3];
    double pd2, inv_nd, m, rho, sqrt_inv_nd;  ///< P/d^2, 1/d (= m/rho = V), m, rho, sqrt(1/d)
  };
  struct alignas(64) HalfAcc {
    double force[3], noise[3], drho, fsum;
  };
  std::vector<HalfIn> hin_;
  std::vector<HalfAcc> hacc_;
  double skin_half2_ = 0;  ///< (skin/2)^2
  SpeciesTransport species_;
  std::vector<std::uint8_t> wall_;
  std::vector<std::int32_t> wall_region_;  ///< wall particle -> WallRegion index (-1: none)
  std::vector<double> wall_depth_;  ///< distance of a wall particle behind its plane [length]
  bool morris_ = false;
  std::vector<double> mass_;
  std::vector<ParticleKind> kinds_;
  std::vector<std::uint64_t> ids_;
  Y y_, ytmp_;
  Rates r0_, r1_;
  std::vector<double> pd2_, inv_nd_;  ///< P_i/d_i^2 and 1/d_i at the state being evaluated
  std::vector<double> vol_;           ///< m_i/rho_i at the state being evaluated
  std::vector<double> sqrt_inv_nd_;   ///< sqrt(1/d_i) (thermal noise only)
  /// Per-thread scratch of the pair loop: one particle's pairs within h as a SIMD block
  /// (sdpd_pair_block.hpp) and the four noise numbers per pair (pair_noise_batch.hpp).
  struct PairScratch {
    SdpdPairBlock block;
    std::array<std::vector<float>, 4> z;
    std::array<std::vector<double>, 4> side;  ///< half path: j-side / noise values per pair
    std::vector<double> m_i;                  ///< half path: m_i per pair (several i per block)
    std::vector<std::uint32_t> seg_end;       ///< half path: end of each particle's pairs
    void reserve(std::size_t n) {
      block.reserve(n);
      if (z[0].size() < n) {
        for (auto& v : z) v.resize(n);
        for (auto& v : side) v.resize(n);
        m_i.resize(n);
      }
    }
    [[nodiscard]] std::size_t bytes() const {
      return block.bytes() + 4 * z[0].capacity() * 4 + 5 * side[0].capacity() * 8 +
             4 * seg_end.capacity();
    }
  };
  std::vector<PairScratch> scratch_;
  double time_ = 0;
};

}  // namespace sadr::fluid
