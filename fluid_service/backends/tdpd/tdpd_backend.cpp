// SPDX-License-Identifier: MIT
/// \file tdpd_backend.cpp
/// tDPD initialisation, Groot-Warren modified velocity-Verlet, limits, health and restart.
#include "tdpd_backend.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "sadr/common/status.hpp"
#include "sadr/fluid/parallel.hpp"
#include "sadr/fluid/state_blob.hpp"
#include "tdpd_forces.hpp"

namespace sadr::fluid {
namespace {

constexpr std::uint64_t kInitialEval = std::uint64_t{1} << 63;  // noise "sub" flag

}  // namespace

double TdpdBackend::fickian_slope_ideal(double rho, double r_cc) {
  // D_F = (rho kappa / (2 d)) int r^2 w_DC dV; d = 3, w_DC = (1 - r/r_cc)^2 -> 2 pi rho r^5/315.
  return 2.0 * std::numbers::pi * rho * std::pow(r_cc, 5) / 315.0;
}

void TdpdBackend::check_model(const FluidModel& model) const {
  // FluidModel::validate() asks for shear_viscosity > 0 with k_B T > 0 (SDPD's
  // fluctuation-dissipation): checked on a copy with a placeholder value.
  FluidModel check = model;
  if (check.shear_viscosity <= 0.0) check.shear_viscosity = 1.0;
  check.validate();
}

void TdpdBackend::setup(const FluidModel& model, const ParticleState& initial,
                        const std::vector<std::vector<double>>& concentrations) {
  params_.apply(model.backend_parameters);
  params_.validate(model.smoothing_length);
  const std::size_t ns = model.species.size();
  n_ = initial.size();
  model_ = model;
  pbox_ = PeriodicBox(model.box);
  const double rc = model.smoothing_length;
  r_cc_ = params_.r_cc > 0.0 ? params_.r_cc : rc;
  sigma_ = std::sqrt(2.0 * params_.gamma * model.temperature);
  kernel_ = Kernel(KernelType::kLucy, model.box.dimension, rc);
  // Verlet skin, narrowed where a small periodic box cannot hold 2 list cutoffs.
  double skin = params_.skin > 0.0 ? params_.skin : model.neighbor_skin;
  for (int k = 0; k < model.box.dimension; ++k) {
    if (model.box.periodic[k]) skin = std::min(skin, model.box.length(k) / (2.0 * rc) - 1.0 - 1e-9);
  }
  const double list_cut = rc * (1.0 + std::max(skin, 0.0));
  builder_ = std::make_unique<CellListBuilder>(model.box, list_cut);
  skin_half2_ = 0.25 * (list_cut - rc) * (list_cut - rc);
  species_.setup(model, initial);
  kappa_.assign(ns, 0.0);
  for (std::size_t s = 0; s < ns; ++s) kappa_[s] = model.species[s].def.diffusivity;
  kinds_ = initial.kinds;
  ids_ = initial.ids;
  wall_.assign(n_, 0);
  for (std::size_t i = 0; i < n_; ++i) wall_[i] = initial.kind(i) == ParticleKind::kWall;
  any_wall_ = std::find(wall_.begin(), wall_.end(), std::uint8_t{1}) != wall_.end();
  rho_valid_ = false;
  walls_ = tdpd::EffectiveWalls{};
  if (params_.effective_walls) {
    walls_.setup(model, params_.a, params_.gamma, r_cc_, model.reference_density);
  }
  reflections_ = 0;
  buffers_ = tdpd::ConcentrationBuffers{};
  if (params_.buffer_axis >= 0) {
    const int k = params_.buffer_axis;
    if (k >= model.box.dimension || !model.box.periodic[k] || !(params_.inflow_length >= 0.0)) {
      throw InvalidArgument("tdpd.buffer_axis = " + std::to_string(k) +
                            " must name a periodic axis (inflow_length >= 0)");
    }
    buffers_ = {k, model.box.lo[k], model.box.lo[k] + params_.inflow_length,
                0.5 * model.box.length(k), params_.inflow_value};
  }

  x_ = initial.positions;
  for (std::size_t i = 0; i < n_; ++i) pbox_.wrap(&x_[3 * i]);
  v_ = initial.velocities.empty() ? std::vector<double>(3 * n_, 0.0) : initial.velocities;
  for (std::size_t i = 0; i < n_; ++i) {
    if (wall_[i]) std::fill_n(v_.begin() + static_cast<std::ptrdiff_t>(3 * i), 3, 0.0);
  }
  c_.assign(ns, std::vector<double>(n_, 0.0));
  for (std::size_t s = 0; s < concentrations.size(); ++s) c_[s] = concentrations[s];
  species_.apply_dirichlet(c_);
  if (buffers_.enabled()) buffers_.apply(x_, species_.transported(), c_);
  q_.assign(ns, std::vector<double>(n_, 0.0));
  q_new_ = q_;
  f_.assign(3 * n_, 0.0);
  have_forces_ = false;
  flux_stale_ = false;
  time_ = 0.0;
  list_ref_x_.clear();
  half_ = tdpd::HalfList{};
  list_builds_ = 0;
}

void TdpdBackend::ensure_neighbors() const {
  bool rebuild = list_ref_x_.size() != x_.size();
  for (std::size_t i = 0; !rebuild && i < n_; ++i) {
    double d[3] = {x_[3 * i] - list_ref_x_[3 * i], x_[3 * i + 1] - list_ref_x_[3 * i + 1],
                   x_[3 * i + 2] - list_ref_x_[3 * i + 2]};
    pbox_.minimum_image(d);
    rebuild = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > skin_half2_;
  }
  if (rebuild) rebuild_neighbors(x_);
}

StabilityLimits TdpdBackend::current_limits() const {
  require_initialized("current_limits()");
  StabilityLimits lim;
  const int d = model_.box.dimension;
  const double rc = model_.smoothing_length;
  const double rho = model_.reference_density;
  double vmax2 = 0.0;
  for (double vk : v_) vmax2 = std::max(vmax2, vk * vk);
  const double vmax = std::sqrt(static_cast<double>(d) * vmax2);
  // Acoustic: a particle may not cross a quarter cutoff per step at the DPD sound speed.
  lim.acoustic = 0.25 * rc / (tdpd::sound_speed(rho, model_.temperature, params_.a) + vmax);
  // Dissipative relaxation: row sum of the pair-friction operator, gamma rho int w_D dV, with
  // the isotropic projection average 1/d; explicit stability needs dt * that <= 1.
  if (params_.gamma > 0.0) {
    lim.viscous =
        static_cast<double>(d) / (params_.gamma * rho * tdpd::ball_integral(d, rc, params_.s1));
  }
  const double g2 = model_.gravity[0] * model_.gravity[0] + model_.gravity[1] * model_.gravity[1] +
                    model_.gravity[2] * model_.gravity[2];
  if (g2 > 0.0) lim.body_force = 0.25 * std::sqrt(rc / std::sqrt(g2));
  // li2015 eq 13: dt < 1 / (rho kappa int w_DC dV), w_DC = (1 - r/r_cc)^2.
  double kmax = 0.0;
  for (const int s : species_.transported()) kmax = std::max(kmax, kappa_[s]);
  if (kmax > 0.0) lim.diffusion = 1.0 / (rho * kmax * tdpd::ball_integral(d, r_cc_, 2.0));
  return lim;
}

void TdpdBackend::check_health(std::uint64_t step_index, std::uint32_t substep) const {
  HealthView h{x_, v_, c_, model_.species, ids_, pbox_};
  h.only_species = &species_.transported();
  fluid::check_health(name(), h, step_index, substep);
}

StepReport TdpdBackend::step(std::uint64_t step_index, double time_step) {
  const UniformSubsteps plan =
      uniform_substeps(current_limits(), model_.max_time_step, model_.force_time_step, time_step);
  const std::uint32_t nsub = plan.count;
  const double dt = plan.dt;
  const auto n = static_cast<std::int64_t>(n_);
  const double lam = params_.lambda;
  const auto& transported = species_.transported();
  v_pred_.resize(3 * n_);
  for (std::uint32_t k = 0; k < nsub; ++k) {
    const std::uint64_t key = (step_index << 16) + k;  // < 2^48 for step_index < 2^32
    species_.set_time(time_);  // the laws of t: at the time of each evaluation
    if (!have_forces_) {
      evaluate(x_, v_, c_, key | kInitialEval, dt, f_, q_);
      have_forces_ = true;
      flux_stale_ = false;
    }
    if (flux_stale_) {
      evaluate(x_, v_, c_, key, dt, f_new_, q_, /*flux_only=*/true);
      flux_stale_ = false;
    }
#pragma omp parallel for schedule(static) if (n >= kMinParallelLight)
    for (std::int64_t ii = 0; ii < n; ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      if (wall_[i]) {
        for (int a = 0; a < 3; ++a) v_pred_[3 * i + a] = 0.0;
        continue;
      }
      for (int a = 0; a < 3; ++a) {
        const std::size_t ia = 3 * i + static_cast<std::size_t>(a);
        x_[ia] += dt * v_[ia] + 0.5 * dt * dt * f_[ia];
        v_pred_[ia] = v_[ia] + lam * dt * f_[ia];
        v_[ia] += 0.5 * dt * f_[ia];
      }
      pbox_.wrap(&x_[3 * i]);
      for (const int s : transported) c_[s][i] += 0.5 * dt * q_[s][i];
    }
    if (walls_.enabled()) {
      reflections_ += walls_.reflect(x_, v_, v_pred_, wall_);
      // The stiff Dirichlet wall term (k dt = 6.8 at the phi cap for kappa = 8.7, dt = 0.01) is
      // not in q_: it is integrated exactly over dt at x(t + dt), on the values at which the
      // rates are evaluated. These (midpoint) values then follow C <- W_dt(C + dt P C) (P: the
      // explicit pair rates), convex combinations within the li2015 diffusion limit: no
      // overshoot of C_w (docs/tdpd.md, "Stiffness"). Neumann sources stay in q_.
      walls_.relax_dirichlet(x_, wall_, transported, kappa_, dt, c_);
    }
    if (buffers_.enabled()) buffers_.apply(x_, transported, c_);
    species_.set_time(time_ + dt);
    evaluate(x_, v_pred_, c_, key, dt, f_new_, q_new_);
#pragma omp parallel for schedule(static) if (n >= kMinParallelLight)
    for (std::int64_t ii = 0; ii < n; ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      if (wall_[i]) continue;
      for (int a = 0; a < 3; ++a) v_[3 * i + a] += 0.5 * dt * f_new_[3 * i + a];
      for (const int s : transported) c_[s][i] += 0.5 * dt * q_new_[s][i];
    }
    std::swap(f_, f_new_);
    std::swap(q_, q_new_);
    time_ += dt;
    check_health(step_index, k);
  }
  StepReport rep;
  rep.time = time_;
  rep.substeps = nsub;
  rep.particles_moved = true;
  rep.stable_dt = plan.limit;
  rep.limiting_criterion = plan.limit_name;
  double vmax2 = 0.0;
  for (std::size_t i = 0; i < n_; ++i) {
    vmax2 = std::max(vmax2, v_[3 * i] * v_[3 * i] + v_[3 * i + 1] * v_[3 * i + 1] +
                                v_[3 * i + 2] * v_[3 * i + 2]);
  }
  rep.max_speed = std::sqrt(vmax2);
  rep.set_density_band(rho_);  // from the last force evaluation, at the current positions
  return rep;
}

std::vector<double> TdpdBackend::densities() const {
  if (rho_valid_) return rho_;
  // Kernel summation rho_i = sum_j m_j W(r_ij) (self included), Lucy kernel of support r_c,
  // masses 1: a number density [1/length^d] on the current (up-to-date within skin) list.
  // Serial over the forward half list (rare: before the first evaluation after initialize()
  // or restore(); evaluations keep rho_ up to date).
  std::vector<double> rho(n_, kernel_.w0());
  const double rc2 = model_.smoothing_length * model_.smoothing_length;
  ensure_neighbors();
  for (std::size_t i = 0; i < n_; ++i) {
    for (const std::uint32_t j : half_.list.of(i)) {
      double d[3] = {x_[3 * i] - x_[3 * j], x_[3 * i + 1] - x_[3 * j + 1],
                     x_[3 * i + 2] - x_[3 * j + 2]};
      pbox_.minimum_image(d);
      const double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
      if (r2 >= rc2) continue;
      const double w = kernel_.w(std::sqrt(r2));
      rho[i] += w;
      rho[j] += w;
    }
  }
  return rho;
}

void TdpdBackend::write_state(ParticleState& out) const {
  out.dimension = model_.box.dimension;
  out.positions = x_;
  out.velocities = v_;
  out.densities = densities();
  out.masses.assign(n_, 1.0);
  out.kinds = kinds_;
  out.ids = ids_;
}

void TdpdBackend::evaluate_current(std::uint64_t noise_step, double dt, std::vector<double>& force,
                                   std::vector<std::vector<double>>& flux) {
  require_initialized("evaluate_current()");
  flux.assign(c_.size(), {});
  evaluate(x_, v_, c_, noise_step << 16, dt, force, flux, /*flux_only=*/false,
           /*dirichlet_rate=*/true);
}

void TdpdBackend::save_state(BlobWriter& w) const {
  w.put<std::uint64_t>(n_);
  w.put<std::uint64_t>(c_.size());
  w.put(time_);
  w.put<std::uint8_t>(have_forces_ ? 1 : 0);
  w.put<std::uint8_t>(flux_stale_ ? 1 : 0);
  w.put_vector(x_);
  w.put_vector(v_);
  w.put_vector(f_);
  for (const auto& c : c_) w.put_vector(c);
  for (const auto& q : q_) w.put_vector(q);
  w.put_vector(list_ref_x_);
}

void TdpdBackend::restore_state(BlobReader& r, std::uint32_t version) {
  if (version < 1 || version > state_version()) {
    throw InvalidArgument("tdpd: blob version " + std::to_string(version) +
                          ", this build reads 1 to " + std::to_string(state_version()));
  }
  if (r.get<std::uint64_t>() != n_ || r.get<std::uint64_t>() != c_.size()) {
    throw InvalidArgument("tdpd: blob from a model with a different particle or species count");
  }
  const double t = r.get<double>();
  const bool hf = r.get<std::uint8_t>() != 0;
  const bool fs = r.get<std::uint8_t>() != 0;
  auto x = r.get_vector<double>(3 * n_);
  auto v = r.get_vector<double>(3 * n_);
  auto f = r.get_vector<double>(3 * n_);
  std::vector<std::vector<double>> c(c_.size()), q(c_.size());
  for (auto& cs : c) cs = r.get_vector<double>(n_);
  for (auto& qs : q) qs = r.get_vector<double>(n_);
  std::vector<double> ref;
  if (version >= 2) {
    ref = r.get_vector<double>();
    if (!ref.empty() && ref.size() != 3 * n_)
      throw InvalidArgument("tdpd: list reference positions in the blob have the wrong size");
  }
  r.expect_end();
  time_ = t;
  have_forces_ = hf;
  // Rates of versions < 3 may contain the Dirichlet wall term: recomputed at the next step.
  flux_stale_ = fs || (version < 3 && walls_.enabled());
  x_ = std::move(x);
  v_ = std::move(v);
  f_ = std::move(f);
  c_ = std::move(c);
  q_ = std::move(q);
  // The same list (and slabs) as the saved run: the half-pair sums are then bit-identical.
  list_ref_x_.clear();
  if (!ref.empty()) rebuild_neighbors(ref);
  rho_valid_ = false;
}

void register_tdpd_backend(BackendRegistry& registry) {
  registry.add("tdpd", [] { return std::make_unique<TdpdBackend>(); });
}

}  // namespace sadr::fluid
