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
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>

#include "sadr/fluid/backend_base.hpp"
#include "sadr/fluid/kernel.hpp"
#include "sadr/fluid/neighbor_list.hpp"
#include "sadr/fluid/pair_terms.hpp"
#include "sadr/fluid/sdpd_pair_block.hpp"
#include "sadr/fluid/species_transport.hpp"
#include "sadr/fluid/stability.hpp"
#include "sadr/fluid/tait_eos.hpp"

namespace sadr::fluid {

class SdpdBackend final : public BackendBase {
 public:
  [[nodiscard]] std::string_view name() const override { return "sdpd"; }
  [[nodiscard]] Capabilities capabilities() const override { return {true, true, true, true}; }
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

 protected:
  void setup(const FluidModel& model, const ParticleState& initial,
             const std::vector<std::vector<double>>& concentrations) override;
  StepReport step(std::uint64_t step_index, double time_step) override;
  void write_state(ParticleState& out) const override;
  std::vector<std::vector<double>>& fields() override { return y_.c; }
  const std::vector<std::vector<double>>& fields() const override { return y_.c; }
  const SpeciesTransport& transport() const override { return species_; }
  void concentrations_changed() override { prepared_ = false; }
  /// 2: + positions of the last list build; 3: + kinds, conveyor flags, inlet holes (open)
  std::uint32_t state_version() const override { return open_ ? 3 : 2; }
  void save_state(BlobWriter& w) const override;
  void restore_state(BlobReader& r, std::uint32_t version) override;

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
  /// phase by slab phase (opens its own parallel region).
  template <class PerSlab>
  void slab_phases(PerSlab&& per_slab);
  /// The same, called by every thread of an enclosing parallel region (or outside one): each
  /// thread takes a contiguous, work-balanced run of the slabs of a phase; slabs wait only for
  /// the conflicting slabs of earlier phases (no barrier). Then, unless `after` is nullptr,
  /// after(first, last) runs on the members of each of the thread's slabs once every slab
  /// writing to them is done. No barrier at the end.
  template <class PerSlab, class After>
  void slab_phases_team(PerSlab&& per_slab, After&& after);
  /// Half path pair loop into hacc_ (hin_ filled, hacc_ zeroed), as slab_phases_team.
  template <int D, class After>
  void half_pairs_team(const Y& y, std::uint64_t noise_step, bool noise_on,
                       const SdpdPairParams& pp, After&& after);
  /// Half path: the rates of particle i from hacc_[i] (acc, acc_noise: 3 entries; drho: 1).
  template <int D>
  void half_rates(std::size_t i, const Y& y, bool noise_on, double* acc, double* acc_noise,
                  double* drho, double& max_visc) const;
  template <int D>
  [[nodiscard]] SdpdPairParams make_pair_params(bool noise_on) const;
  /// One predictor-corrector sub-step of the half path with the continuity density in two
  /// parallel regions (one per force evaluation; the per-particle loops ride along): returns
  /// the sub-step length.
  template <int D>
  double fused_substep(std::uint64_t step_index, std::uint64_t key, double remaining,
                       std::uint32_t sub, StepReport& rep, bool& unhealthy);
  /// Fills hin_ from y_ (the noise factor if noise_on), zeroes hacc_, sets y_moved_.
  void prepare_half(bool noise_on);
  [[nodiscard]] bool fused_ok() const {
    return half_ok_ && model_.density_mode == DensityMode::kContinuity;
  }
  void ensure_neighbors(const std::vector<double>& x);
  void rebuild_neighbors(const std::vector<double>& x);  ///< list + slabs at positions x
  StabilityLimits limits(const Y& y, const Rates& r) const;
  /// limits() from the particle maxima/minimum it reduces (max |v|^2 and |a_body|^2 over fluid
  /// particles, min rho).
  StabilityLimits limits_from(double vmax2, double rho_min, double amax2, double max_visc_sum,
                              double max_k_sum, const Y& y) const;
  /// Whether the position xi of particle i has moved more than skin/2 since the list build.
  [[nodiscard]] bool moved_since_build(std::size_t i, const double* xi) const {
    double d[3] = {xi[0] - list_ref_x_[3 * i], xi[1] - list_ref_x_[3 * i + 1],
                   xi[2] - list_ref_x_[3 * i + 2]};
    pbox_.minimum_image(d);
    return d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > skin_half2_;
  }
  /// Half path: hin_[i] from the state y.
  void fill_half_in(std::size_t i, const Y& y, bool noise_on) {
    const double nd_inv = mass_[i] / y.rho[i];  // 1/d_i, bitwise the volume m_i/rho_i
    HalfIn& p = hin_[i];
    for (int a = 0; a < 3; ++a) p.v[a] = y.v[3 * i + a];
    p.pd2 = eos_.pressure(y.rho[i]) * nd_inv * nd_inv;
    p.inv_nd = nd_inv;
    p.m = mass_[i];
    p.rho = y.rho[i];
    p.sqrt_inv_nd = noise_on ? std::sqrt(nd_inv) : 0.0;
  }
  void check_health(std::uint64_t step_index, std::uint32_t substep) const;
  /// Open boundary: kinds by position, recycling, inflow velocity and density (after every
  /// sub-step and at initialize()).
  void apply_open_boundary(double dt);
  /// Open boundary: zero-gradient values of the `target` buffer particles (inlet: density;
  /// outlet: velocity) from the fluid particles with axis coordinate in [lo, hi).
  void extrapolate_from_fluid(ParticleKind target, double lo, double hi);

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
  static constexpr std::uint32_t kSlabReach = 2;        ///< slab width >= list cutoff / kSlabReach
  static constexpr std::uint32_t kMaxSubsteps = 65535;  ///< noise key: (step << 16) | substep
  bool half_ok_ = false;
  std::uint32_t slab_count_ = 0;
  bool slab_wrap_ = false;                   ///< slab axis periodic
  std::vector<std::uint32_t> slab_of_;       ///< particle -> slab
  std::vector<std::uint32_t> slab_start_;    ///< CSR over slabs (slab_count_ + 1)
  std::vector<std::uint32_t> slab_members_;  ///< particles of each slab, by index
  /// Per colour: prefix sums of the work (members + forward list entries) of its slabs, for
  /// the work-balanced split among threads (slab_phases_team).
  std::array<std::vector<std::uint64_t>, kSlabReach + 1> colour_work_;
  /// Per slab: the number of the last slab pass that has finished it (slab_phases_team).
  std::unique_ptr<std::atomic<std::uint32_t>[]> slab_done_;
  std::uint32_t slab_done_count_ = 0;
  std::uint32_t slab_epoch_ = 0;  ///< number of the current slab pass (never 0)
  void next_slab_pass();          ///< before each parallel region running slab_phases_team
  /// fused_substep: hin_ holds y_ (with the noise factor if temperature > 0), hacc_ is zero and
  /// y_moved_ tells whether y_.x has moved more than skin/2 since the list build. Cleared by
  /// every other use of hin_/hacc_ (evaluate) and by initialize/restore.
  bool prepared_ = false;
  bool y_moved_ = true;
  double report_vmax2_ = 0, report_rho_min_ = 0, report_rho_max_ = 0;  ///< of the last corrector
  /// fused_substep: per-thread maxima / minima / flags of the per-particle work
  struct alignas(64) FusedPartial {
    double max_visc = 0, vmax2 = 0, amax2 = 0;
    double rho_min = std::numeric_limits<double>::infinity(), rho_max = 0;
    int moved = 0, bad = 0;
  };
  std::vector<FusedPartial> fused_partials_;
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
  std::vector<ParticleKind> kinds_;     ///< current kinds (inlet/outlet change at open boundaries)
  bool open_ = false;                   ///< model_.open_boundary.enabled
  std::vector<std::uint8_t> buffer_;    ///< 1: inlet or outlet (no forces, no noise, fixed rho)
  std::vector<std::uint8_t> conveyor_;  ///< inlet particle holding a conveyor slot (saved)
  std::vector<double> holes_;           ///< empty conveyor slots, 3 coordinates each (saved)
  /// apply_open_boundary scratch: fluid next to the outlet, conveyor crossings, outlets
  std::vector<std::uint32_t> slab_fluid_, ob_crossing_, ob_outlets_;
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
