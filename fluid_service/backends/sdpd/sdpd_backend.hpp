// SPDX-License-Identifier: MIT
/// \file sdpd_backend.hpp
/// Smoothed dissipative particle dynamics (Espanol & Revenga 2003) with deterministic
/// reaction-diffusion (docs/method.md), integrated with the explicit trapezoidal
/// predictor-corrector of drawert2019 eq 24 on Y = [x, v, rho, C].
///
/// The units, one file each:
///  - sdpd_backend.cpp: setup, neighbour lists, the evaluation dispatch, memory;
///  - sdpd_gather.cpp: the pair loop over full lists (walls, species, reactions, Morris walls);
///  - sdpd_half_path.cpp: the bulk-fluid pair loop, each pair once, on the core SlabScheduler
///    (measured 1.5-2x faster per step on the issue-4 benchmark, docs/fluid-core.md 6);
///  - sdpd_integrator.cpp: the predictor-corrector sub-step loop;
///  - sdpd_fused_step.cpp: the bulk-fluid sub-step with the per-particle work in the pair loops;
///  - sdpd_limits.cpp: stability limits and the health check;
///  - sdpd_restart.cpp: the saved state;
///  - sdpd_open_boundary.*: the open channel; sdpd_morris_walls.hpp: Morris walls;
///  - sdpd_adami_walls.cpp: Adami walls (wall pressure and velocity from the fluid);
///  - sdpd_body_forces.cpp: the force and torque of the fluid on bodies (fluid.body_forces);
///  - sdpd_moving_bodies.cpp: bodies whose wall particles move (FluidModel::moving_bodies).
/// Both pair loops are bit-identical on any thread count (no atomics). Wall particles (kind kWall)
/// are not integrated (a moving body's are placed by sdpd_moving_bodies.cpp), keep v = v_wall,
/// evolve their density by continuity (so the fluid cannot penetrate) and hold their species values
/// (Dirichlet) or are excluded (no-flux / Neumann ghost).
#pragma once

#include <array>
#include <cmath>
#include <limits>
#include <memory>

#include "sadr/fluid/backend_base.hpp"
#include "sadr/fluid/backend_registry.hpp"
#include "sadr/fluid/kernel.hpp"
#include "sadr/fluid/neighbor_list.hpp"
#include "sadr/fluid/pair_terms.hpp"
#include "sadr/fluid/slab_scheduler.hpp"
#include "sadr/fluid/species_transport.hpp"
#include "sadr/fluid/stability.hpp"
#include "sadr/fluid/tait_eos.hpp"
#include "sdpd_morris_walls.hpp"
#include "sdpd_open_boundary.hpp"
#include "sdpd_pair_block.hpp"
#include "sdpd_pair_physics.hpp"

namespace sadr::fluid {

class SdpdBackend final : public BackendBase {
 public:
  [[nodiscard]] std::string_view name() const override { return "sdpd"; }
  [[nodiscard]] double time() const override { return time_; }

  /// Rates of change at one state (public for the tests of the pair loop).
  struct Rates {
    std::vector<double> acc;        ///< deterministic acceleration, 3N [length/time^2]
    std::vector<double> acc_noise;  ///< noise acceleration times sqrt(dt), 3N (empty if k_B T = 0)
    std::vector<double> drho;       ///< N [mass/length^d/time]
    std::vector<std::vector<double>> dc;  ///< [species][N] [C/time]
    double max_k_sum = 0;                 ///< max_i sum_j K_ij over fluid i [1/length^2]
    double max_visc_sum = 0;  ///< max_i (a + b)/rho_i sum_j V_j F_ij [1/(length^2)] / viscosity
    /// Transport velocity only (else empty): s = v~ - v, 3N [length/time]; positions move
    /// with v + s (sdpd_transport_velocity.cpp).
    std::vector<double> shift;
    /// Forces on bodies only (else empty): per body of FluidModel::body_forces the force (3)
    /// and torque (3) the fluid exerts on it at this state (sdpd_body_forces.cpp).
    std::vector<double> body;
  };
  /// Evaluates the rates at the current state with the noise of `noise_step` (testing aid).
  void evaluate_current(std::uint64_t noise_step, Rates& out);
  /// The same with the transport-velocity terms of a sub-step dt (transport velocity on).
  void evaluate_current(std::uint64_t noise_step, double dt, Rates& out);
  /// Whether the transport-velocity formulation is on (parameter transport_velocity).
  [[nodiscard]] bool transport_velocity() const { return tvf_; }
  /// Adami walls (wall_model kAdami): whether on, and the wall values of the last evaluation
  /// (sdpd_adami_walls.cpp): pressure p_w (N; 0 off the walls) and the velocity of the viscous
  /// term (3N; 0 off the walls and at walls without a fluid neighbour) (testing aid).
  [[nodiscard]] bool adami_walls() const { return adami_; }
  [[nodiscard]] const std::vector<double>& adami_wall_pressure() const { return adami_p_; }
  [[nodiscard]] const std::vector<double>& adami_wall_velocity() const { return adami_v_; }
  /// The mean curvature per FluidModel::wall_tangents entry (Adami walls; testing aid).
  [[nodiscard]] const std::vector<double>& adami_curvature() const { return adami_kappa_; }
  /// Heap bytes held by the backend (state, scratch, neighbour list), for the benchmark.
  [[nodiscard]] std::size_t memory_bytes() const;
  /// Stability limits at the current state (evaluates the rates once, on a copy of the state
  /// into scratch rates: the trajectory is left as it is).
  [[nodiscard]] StabilityLimits current_limits();
  /// current_limits() under max_time_step / force_time_step (the rule of every sub-step).
  [[nodiscard]] SubstepBound current_substep_bound() override {
    return substep_bound(current_limits(), model_.max_time_step, model_.force_time_step);
  }
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
  std::uint32_t state_version() const override { return open_.enabled() ? 3 : 2; }
  void save_state(BlobWriter& w) const override;
  void restore_state(BlobReader& r, std::uint32_t version) override;

 private:
  struct Y {
    std::vector<double> x, v, rho;
    std::vector<std::vector<double>> c;
  };
  /// Per-thread scratch of the pair loops: the pairs of one or a few particles as a SIMD block
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
  /// fused_substep: per-thread maxima / minima / flags of the per-particle work
  struct alignas(64) FusedPartial {
    double max_visc = 0, vmax2 = 0, amax2 = 0;
    double rho_min = std::numeric_limits<double>::infinity(), rho_max = 0;
    int moved = 0, bad = 0;
  };
  /// The terms of the full-list gather at one evaluation (sdpd_gather.cpp).
  struct GatherTerms;

  // --- evaluation (sdpd_backend.cpp dispatches; sdpd_gather.cpp, sdpd_half_path.cpp)
  void evaluate(Y& y, std::uint64_t noise_step, Rates& out, bool with_noise);
  template <int D>
  void evaluate_gather(Y& y, std::uint64_t noise_step, Rates& out, bool noise_on);
  template <int D>
  void summation_gather(Y& y);
  /// The rates of particle i from its full list (sdpd_gather.cpp): the pair sums of
  /// gather_block (fluid particle, stationary walls: the SIMD block) or gather_pairs (wall
  /// particles, Morris walls: pair by pair), then its rates.
  template <int D>
  struct GatherSums;
  template <int D>
  void gather_particle(std::size_t i, const Y& y, std::uint64_t noise_step, const GatherTerms& t,
                       PairScratch& sc, Rates& out, double& max_k_sum, double& max_visc);
  template <int D>
  void gather_block(std::size_t i, const Y& y, const GatherTerms& t, PairScratch& sc,
                    GatherSums<D>& s, Rates& out);
  template <int D>
  void gather_pairs(std::size_t i, const Y& y, const GatherTerms& t, PairScratch& sc,
                    GatherSums<D>& s, Rates& out);
  /// Pair geometry of (i, j) at positions x; false if r >= h.
  template <int D>
  bool pair_geometry(const double* x, std::size_t i, std::uint32_t j, PairGeometry<D>& g) const {
    double d[3] = {x[3 * i] - x[3 * j], x[3 * i + 1] - x[3 * j + 1], x[3 * i + 2] - x[3 * j + 2]};
    pbox_.minimum_image(d);
    double r2 = 0;
    for (int a = 0; a < D; ++a) {
      g.x[a] = d[a];
      r2 += d[a] * d[a];
    }
    const double h = kernel_.support();
    if (r2 >= h * h) return false;
    g.r2 = r2;
    g.r = std::sqrt(r2);
    g.f = kernel_.f(g.r);
    g.inv_r2 = 1.0 / r2;
    return true;
  }
  /// The momentum pair force on the fluid particle i from j (any kind), added to `force`, with
  /// the wall model of a wall j: Morris et al. 1997, beta (v_i - v_w) in the viscous term and v in
  /// the pressure term; Adami et al. 2012, v_i minus the wall's extrapolated velocity (pd2_[j]
  /// holds its extrapolated pressure); else v = v_i - v_j. Shared by the gather (sdpd_gather.cpp)
  /// and the forces on bodies (sdpd_body_forces.cpp). Returns Morris' beta (1 otherwise), which
  /// also scales Dirichlet species.
  template <int D>
  double fluid_pair_momentum(const Y& y, std::size_t i, std::uint32_t j, const PairGeometry<D>& g,
                             const std::array<double, D>& v, const SdpdMomentumTerm& momentum,
                             double h, std::array<double, D>& force) const {
    const double inv_didj = inv_nd_[i] * inv_nd_[j];
    if (morris_.enabled() && morris_.extrapolates(j)) {
      const double beta = morris_.beta<D>(&y.x[3 * i], g.x.data(), j, h);
      std::array<double, D> vb;
      for (int a = 0; a < D; ++a) vb[a] = beta * v[a];
      const SdpdMomentumTerm pressure_only{0.0};
      pressure_only(g, pd2_[i], pd2_[j], inv_didj, v, force);
      const SdpdMomentumTerm viscous_only{momentum.friction};
      viscous_only(g, 0.0, 0.0, inv_didj, vb, force);
      return beta;
    }
    if (adami_ && wall_[j]) {
      std::array<double, D> va;
      for (int a = 0; a < D; ++a) va[a] = y.v[3 * i + a] - adami_v_[3 * j + a];
      momentum(g, pd2_[i], pd2_[j], inv_didj, va, force);
      return 1.0;
    }
    momentum(g, pd2_[i], pd2_[j], inv_didj, v, force);
    return 1.0;
  }
  /// Transport velocity (sdpd_transport_velocity.cpp): out.shift and the A-tensor term of
  /// out.acc at the state y whose rates `out` holds (pd2_, vol_ of y), for a sub-step dt.
  void apply_transport_velocity(const Y& y, double dt, Rates& out);
  /// Adami walls (sdpd_adami_walls.cpp): adami_p_, adami_v_ and, for every wall particle,
  /// pd2_ = p_w/d_w^2 with rho_w from p_w by the inverse Tait law, from the fluid state y
  /// (pd2_, inv_nd_, vol_ of y already filled).
  template <int D>
  void adami_wall_values(const Y& y);
  /// Adami walls on the geometry's surfaces (sdpd_adami_walls.cpp): adami_tangent_ and
  /// adami_kappa_ from model_.wall_tangents and the initial wall positions in y_.x.
  void adami_surfaces();
  template <int D>
  void transport_velocity_terms(const Y& y, double dt, Rates& out);
  /// Wall-free, species-free systems: each pair evaluated once (sdpd_half_path.cpp).
  template <int D>
  void evaluate_half(Y& y, std::uint64_t noise_step, Rates& out, bool noise_on);
  template <int D>
  void summation_half(Y& y);
  /// Half path pair loop into hacc_ (hin_ filled, hacc_ zeroed), called by every thread of a
  /// parallel region after slabs_.next_pass(); `after` as SlabScheduler::run_team.
  template <int D>
  void half_pairs_team(const Y& y, std::uint64_t noise_step, bool noise_on,
                       const SdpdPairParams& pp, SlabMembersFn after);
  /// Half path: the rates of particle i from hacc_[i] (acc, acc_noise: 3 entries; drho: 1).
  template <int D>
  void half_rates(std::size_t i, const Y& y, bool noise_on, double* acc, double* acc_noise,
                  double* drho, double& max_visc) const;
  template <int D>
  [[nodiscard]] SdpdPairParams make_pair_params(bool noise_on) const;
  /// Fills hin_ from y_ (the noise factor if noise_on), zeroes hacc_, sets y_moved_.
  void prepare_half(bool noise_on);
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
  /// Body acceleration of particle i at concentrations c: gravity plus the Boussinesq term.
  void body_acceleration(std::size_t i, const std::vector<std::vector<double>>& c,
                         double* a) const {
    const auto& bq = model_.boussinesq;
    for (int k = 0; k < 3; ++k) a[k] = model_.gravity[k];
    if (bq.species >= 0) {
      const double b = bq.coefficient * (c[bq.species][i] - bq.reference);
      for (int k = 0; k < 3; ++k) a[k] += b * bq.direction[k];
    }
  }
  void ensure_scratch() {
    if (scratch_.size() < static_cast<std::size_t>(max_threads()))
      scratch_.resize(static_cast<std::size_t>(max_threads()));
  }

  // --- integration (sdpd_integrator.cpp, sdpd_fused_step.cpp)
  /// One predictor-corrector sub-step of the general path: returns its length.
  double general_substep(std::uint64_t step_index, std::uint64_t key, double remaining,
                         std::uint32_t sub, StepReport& rep);
  /// One sub-step of the half path with the continuity density in two parallel regions (one
  /// per force evaluation; the per-particle loops ride along): returns the sub-step length.
  template <int D>
  double fused_substep(std::uint64_t step_index, std::uint64_t key, double remaining,
                       std::uint32_t sub, StepReport& rep, bool& unhealthy);
  [[nodiscard]] bool fused_ok() const {
    return half_ok_ && model_.density_mode == DensityMode::kContinuity;
  }

  // --- neighbour lists (sdpd_backend.cpp)
  void ensure_neighbors(const std::vector<double>& x);
  void rebuild_neighbors(const std::vector<double>& x);  ///< list + slabs at positions x
  /// Whether the position xi of particle i has moved more than skin/2 since the list build.
  [[nodiscard]] bool moved_since_build(std::size_t i, const double* xi) const {
    double d[3] = {xi[0] - list_ref_x_[3 * i], xi[1] - list_ref_x_[3 * i + 1],
                   xi[2] - list_ref_x_[3 * i + 2]};
    pbox_.minimum_image(d);
    return d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > skin_half2_;
  }

  // --- limits and health (sdpd_limits.cpp)
  StabilityLimits limits(const Y& y, const Rates& r) const;
  /// limits() from the particle maxima/minimum it reduces (max |v|^2 and |a_body|^2 over fluid
  /// particles, min rho).
  StabilityLimits limits_from(double vmax2, double rho_min, double amax2, double max_visc_sum,
                              double max_k_sum, const Y& y) const;
  void check_health(std::uint64_t step_index, std::uint32_t substep) const;
  /// Open channel after a sub-step (and at setup): kinds, recycling, buffer values, sites.
  void apply_open_boundary(double dt);

  static constexpr std::uint32_t kMaxSubsteps = 65535;  ///< noise key: (step << 16) | substep
  /// The NumericalFailure of a coupling step that needs more than kMaxSubsteps sub-steps,
  /// naming the binding limit and the scene key that shortens the step.
  [[noreturn]] static void throw_too_many_substeps(std::uint64_t step_index,
                                                   const std::string& limit_name, double limit);

  FluidModel model_;
  Kernel kernel_;
  TaitEos eos_;
  PeriodicBox pbox_;
  std::unique_ptr<CellListBuilder> builder_;
  NeighborList nlist_;              ///< full lists, or forward lists on the half path
  std::vector<double> list_ref_x_;  ///< positions at the last list build (saved: exact restarts)
  std::uint64_t list_builds_ = 0;
  double skin_half2_ = 0;  ///< (skin/2)^2
  /// Half-pair path (no wall particles, no Morris walls, no transported species, no reactions):
  /// slabs along the last active axis, assigned at each list build.
  bool half_ok_ = false;
  /// Transport-velocity formulation (parameters transport_velocity, shift_pressure): on
  /// the full-list gather path only; p_b [pressure].
  bool tvf_ = false;
  double tvf_shift_pressure_ = 0;
  /// Adami walls (wall_model kAdami; full-list gather path): the wall values of the evaluation.
  bool adami_ = false;
  std::vector<double> adami_p_, adami_v_;
  /// Adami walls made by a scene's geometry (FluidModel::wall_tangents): wall particle ->
  /// WallTangents entry (-1: none; empty: no tangents), whose plane places the no-slip surface,
  /// and the surface's mean curvature at the entry's surface point (adami_surfaces()).
  std::vector<std::int32_t> adami_tangent_;
  std::vector<double> adami_kappa_;
  SlabScheduler slabs_;
  /// fused_substep: hin_ holds y_ (with the noise factor if temperature > 0), hacc_ is zero and
  /// y_moved_ tells whether y_.x has moved more than skin/2 since the list build. Cleared by
  /// every other use of hin_/hacc_ (evaluate) and by initialize/restore.
  bool prepared_ = false;
  bool y_moved_ = true;
  double report_vmax2_ = 0, report_rho_min_ = 0, report_rho_max_ = 0;  ///< of the last corrector
  std::vector<FusedPartial> fused_partials_;
  std::vector<HalfIn> hin_;
  std::vector<HalfAcc> hacc_;
  SpeciesTransport species_;
  std::vector<std::uint8_t> wall_;
  MorrisWalls morris_;
  OpenChannel open_;
  std::vector<double> mass_;
  std::vector<ParticleKind> kinds_;  ///< current kinds (inlet/outlet change at open boundaries)
  std::vector<std::uint64_t> ids_;
  Y y_, ytmp_;
  Rates r0_, r1_;
  std::vector<double> pd2_, inv_nd_;  ///< P_i/d_i^2 and 1/d_i at the state being evaluated
  std::vector<double> vol_;           ///< m_i/rho_i at the state being evaluated
  std::vector<double> sqrt_inv_nd_;   ///< sqrt(1/d_i) (thermal noise only)
  std::vector<PairScratch> scratch_;
  double time_ = 0;

  // --- forces on bodies (sdpd_body_forces.cpp): FluidModel::body_forces
  struct Bodies {
    std::vector<std::vector<std::uint32_t>> walls;  ///< each body's wall particles
    std::vector<std::array<double, 3>> reference;   ///< torque reference: their centroid
    std::vector<double> sum;                        ///< integral of Rates::body over the step
    double duration = 0;                            ///< length integrated [time]
    /// Moving bodies: per group the index of the moving body its reference follows (-1: none)
    /// and the reference at t = 0 (sdpd_moving_bodies.cpp).
    std::vector<std::int32_t> moving;
    std::vector<std::array<double, 3>> reference0;
  };
  Bodies bodies_;
  /// bodies_ from the model's groups (each must hold a wall particle) at the initial state.
  void setup_bodies();
  /// out.body at the state y whose pair terms evaluate_gather just filled (pd2_, inv_nd_, the
  /// Adami wall values).
  template <int D>
  void body_forces_at(const Y& y, Rates& out) const;
  /// Adds the sub-step's trapezoidal mean, dt (r0_.body + r1_.body) / 2, to bodies_.sum.
  void accumulate_body_forces(double dt);
  /// The step's mean force and torque per body (StepReport::body_forces); resets the sums.
  std::vector<BodyForce> take_body_forces();

  // --- moving bodies (sdpd_moving_bodies.cpp): FluidModel::moving_bodies
  struct Moving {
    std::vector<std::int32_t> of;         ///< per particle: its entry below, -1 (empty: none)
    std::vector<std::uint32_t> particle;  ///< the moving wall particles
    std::vector<std::uint32_t> body;      ///< their body (index into model_.moving_bodies)
    std::vector<double> x0;               ///< their positions at t = 0, 3 each
    std::vector<std::uint32_t> tangent;   ///< wall_tangents entries of moving particles
    std::vector<std::uint32_t> tangent_body;
    std::vector<double> n0;  ///< those entries' normals at t = 0, 3 each
    double time = 0;         ///< the time of the last placement
  };
  Moving moving_;
  /// moving_ from the model at the initial state (after setup_bodies), placed at t = 0.
  void setup_moving_bodies();
  /// Places the moving bodies' wall particles of y at time t (positions, velocities), turns
  /// their wall_tangents normals and moves the body force references to t.
  void move_bodies(Y& y, double t);
  /// The acceleration of wall particle w at the last placement (0 unless it moves and turns).
  [[nodiscard]] std::array<double, 3> moving_acceleration(std::size_t w) const;
};

template <int D>
inline void SdpdBackend::half_rates(std::size_t i, const Y& y, bool noise_on, double* acc,
                                    double* acc_noise, double* drho, double& max_visc) const {
  const HalfAcc& ai = hacc_[i];
  max_visc = std::max(max_visc, ai.fsum / y.rho[i]);
  const double inv_m = 1.0 / mass_[i];
  double body[3];
  body_acceleration(i, y.c, body);
  for (int a = 0; a < 3; ++a) acc[a] = a < D ? ai.force[a] * inv_m + body[a] : 0.0;
  if (noise_on) {
    for (int a = 0; a < 3; ++a) acc_noise[a] = a < D ? ai.noise[a] * inv_m : 0.0;
  }
  *drho = ai.drho;
}

template <int D>
SdpdPairParams SdpdBackend::make_pair_params(bool noise_on) const {
  // a = b = c_D eta (sdpd::viscosity_factor; LAMMPS' 5/3 in 2D gives 1.042 eta)
  const double h = kernel_.support();
  const double h2 = h * h;
  const double c_d = sdpd::viscosity_factor<D>();
  const SdpdMomentumTerm momentum{c_d * model_.shear_viscosity};
  const ContinuityTerm continuity{model_.density_diffusion * h * model_.sound_speed, 0.01 * h2};
  SdpdPairParams pp;
  pp.inv_h = kernel_.inv_support();
  pp.f_coef = kernel_.f_coef();
  pp.sqrt_f_coef = kernel_.sqrt_f_coef();
  pp.lucy = kernel_.type() == KernelType::kLucy;
  pp.friction = momentum.friction;
  pp.delta_h_c0 = continuity.delta_h_c0;
  pp.eps_h2 = continuity.eps_h2;
  pp.noise_amp = std::sqrt(2.0 * model_.temperature * c_d * model_.shear_viscosity);
  pp.noise = noise_on;
  return pp;
}

/// Registers "sdpd" (called by the generated register_builtin_backends(), backends.cmake).
void register_sdpd_backend(BackendRegistry& registry);

}  // namespace sadr::fluid
