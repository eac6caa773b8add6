// SPDX-License-Identifier: MIT
#include "sdpd_backend.hpp"
#include "sadr/fluid/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "sadr/common/status.hpp"
#include "sadr/fluid/state_blob.hpp"

namespace sadr::fluid {

namespace {
/// What only sdpd asks of an initial state (validate_initial_state() checked the rest).
void check_initial(const FluidModel& model, const ParticleState& s) {
  const PeriodicBox pb(model.box);
  for (std::size_t i = 0; i < s.size(); ++i) {
    const ParticleKind k = s.kind(i);
    const auto& ob = model.open_boundary;
    if (!ob.enabled && (k == ParticleKind::kInlet || k == ParticleKind::kOutlet)) {
      throw InvalidArgument("particle " + std::to_string(i) + " has kind " +
                            std::string(to_string(k)) +
                            ", which needs an open boundary (model.open_boundary; without it: "
                            "fluid, wall)");
    }
    if (ob.enabled && k != ParticleKind::kWall) {
      const double xa = s.positions[3 * i + static_cast<std::size_t>(ob.axis)];
      if (!(xa >= ob.inlet_lo && xa <= ob.outlet_hi)) {
        throw InvalidArgument("particle " + std::to_string(i) + " (kind " +
                              std::string(to_string(k)) + ") at " + format_value(xa) +
                              " along the flow axis lies outside the open channel [inlet_lo, "
                              "outlet_hi] = [" +
                              format_value(ob.inlet_lo) + ", " + format_value(ob.outlet_hi) +
                              "] (only wall particles may)");
      }
    }
    if (!pb.inside(&s.positions[3 * i])) {
      throw InvalidArgument("particle " + std::to_string(i) +
                            " lies outside the box on a walled axis");
    }
  }
}
}  // namespace

void SdpdBackend::setup(const FluidModel& model, const ParticleState& initial,
                        const std::vector<std::vector<double>>& concentrations) {
  check_initial(model, initial);
  if (!model.backend_parameters.empty()) {
    throw InvalidArgument("sdpd: unknown parameter '" + model.backend_parameters.begin()->first +
                          "' (this backend takes none beyond density_diffusion, diffusion_eps, "
                          "density_band, neighbor_skin)");
  }
  if (!(model.sound_speed > 0)) {
    throw InvalidArgument("sdpd: sound_speed = " + format_value(model.sound_speed) +
                          " (must be > 0: the Tait equation of state needs c_0, at least 10x the "
                          "largest flow speed)");
  }
  model_ = model;
  const int dim = model.box.dimension;
  kernel_ = Kernel(parse_kernel(model.kernel), dim, model.smoothing_length);
  eos_ = TaitEos(model.reference_density, model.sound_speed);
  pbox_ = PeriodicBox(model.box);
  const double skin = model.neighbor_skin * model.smoothing_length;
  builder_ = std::make_unique<CellListBuilder>(model.box, model.smoothing_length + skin);
  skin_half2_ = 0.25 * skin * skin;
  const std::size_t n = initial.size();
  mass_ = initial.masses;
  kinds_.assign(n, ParticleKind::kFluid);
  wall_.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    kinds_[i] = initial.kind(i);
    wall_[i] = kinds_[i] == ParticleKind::kWall ? 1 : 0;
  }
  // Morris walls: region and depth of every wall particle behind its region's plane.
  morris_ = model.wall_model == WallModel::kMorrisExtrapolated;
  wall_region_.assign(n, -1);
  wall_depth_.assign(n, 0.0);
  if (morris_) wall_region_ = model.assign_wall_regions(initial);
  for (std::size_t i = 0; i < n && morris_; ++i) {
    const int w = wall_region_[i];
    if (w < 0) continue;
    const auto& reg = model.wall_regions[static_cast<std::size_t>(w)];
    double d = 0;
    for (int a = 0; a < 3; ++a)
      d -= reg.inward_normal[a] * (initial.positions[3 * i + a] - reg.surface_point[a]);
    wall_depth_[i] = std::max(d, 0.0);
  }
  ids_ = initial.ids;
  if (ids_.empty()) {
    ids_.resize(n);
    for (std::size_t i = 0; i < n; ++i) ids_[i] = i;
  }
  y_.x = initial.positions;
  for (std::size_t i = 0; i < n; ++i) pbox_.wrap(&y_.x[3 * i]);
  y_.v = initial.velocities.empty() ? std::vector<double>(3 * n, 0.0) : initial.velocities;
  for (std::size_t i = 0; i < n; ++i) {
    for (int a = dim; a < 3; ++a) y_.v[3 * i + a] = 0.0;
    if (wall_[i]) y_.v[3 * i] = y_.v[3 * i + 1] = y_.v[3 * i + 2] = 0.0;
  }
  y_.rho = initial.densities;
  y_.c.assign(model.species.size(), std::vector<double>(n, 0.0));
  for (std::size_t s = 0; s < concentrations.size(); ++s) y_.c[s] = concentrations[s];
  species_.setup(model_, initial);
  species_.apply_dirichlet(y_.c);
  list_ref_x_.clear();
  nlist_ = {};
  open_ = model.open_boundary.enabled;
  buffer_.assign(n, 0);
  conveyor_.assign(n, 0);  // initial inlet particles are conveyor particles
  for (std::size_t i = 0; i < n && open_; ++i) {
    const double s = y_.x[3 * i + static_cast<std::size_t>(model.open_boundary.axis)];
    conveyor_[i] = !wall_[i] && s < model.open_boundary.fluid_lo;
    if (!wall_[i])
      kinds_[i] = s < model.open_boundary.fluid_lo ? ParticleKind::kInlet : ParticleKind::kFluid;
  }
  half_ok_ = !open_ && !morris_ && species_.transported().empty() && !species_.has_reactions() &&
             std::none_of(wall_.begin(), wall_.end(), [](std::uint8_t w) { return w != 0; });
  holes_.clear();
  if (open_) apply_open_boundary(0.0);  // (reaction sites follow the kinds it sets)
  time_ = 0;
  prepared_ = false;
}

void SdpdBackend::ensure_neighbors(const std::vector<double>& x) {
  bool rebuild = list_ref_x_.size() != x.size();
  if (!rebuild) {
    const auto ni = static_cast<std::int64_t>(x.size() / 3);
    int moved = 0;
#pragma omp parallel for schedule(static) if (ni > kMinParallelLight) reduction(max : moved)
    for (std::int64_t ii = 0; ii < ni; ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      if (moved_since_build(i, &x[3 * i])) moved = 1;
    }
    rebuild = moved != 0;
  }
  if (rebuild) rebuild_neighbors(x);
}

// rebuild_neighbors: sdpd_half_pairs.hpp (with the slabs it assigns)

StabilityLimits SdpdBackend::limits(const Y& y, const Rates& r) const {
  const std::size_t n = mass_.size();
  double vmax2 = 0, rho_min = std::numeric_limits<double>::infinity(), amax2 = 0;
  const auto& bq = model_.boussinesq;
  const auto ni = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static) if (ni > kMinParallelLight) reduction(max             \
                                                                                : vmax2, amax2) \
    reduction(min                                                                               \
              : rho_min)
  for (std::int64_t ii = 0; ii < ni; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    if (wall_[i]) continue;
    const double* v = &y.v[3 * i];
    vmax2 = std::max(vmax2, v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    rho_min = std::min(rho_min, y.rho[i]);
    double a[3] = {model_.gravity[0], model_.gravity[1], model_.gravity[2]};
    if (bq.species >= 0) {
      const double b = bq.coefficient * (y.c[bq.species][i] - bq.reference);
      for (int k = 0; k < 3; ++k) a[k] += b * bq.direction[k];
    }
    amax2 = std::max(amax2, a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  }
  return limits_from(vmax2, rho_min, amax2, r.max_visc_sum, r.max_k_sum, y);
}

StabilityLimits SdpdBackend::limits_from(double vmax2, double rho_min, double amax2,
                                         double max_visc_sum, double max_k_sum, const Y& y) const {
  StabilityLimits lim;
  const double h = kernel_.support();
  // SPEC 5 coefficients are Morris' for the smoothing length h_M = h/2 (support = 2 h_M).
  const double hm = 0.5 * h;
  lim.acoustic = 0.25 * hm / (model_.sound_speed + std::sqrt(vmax2));
  if (model_.shear_viscosity > 0 && std::isfinite(rho_min)) {
    lim.viscous = 0.125 * rho_min * hm * hm / model_.shear_viscosity;
    if (max_visc_sum > 0)
      lim.viscous = std::min(lim.viscous, 1.0 / (model_.shear_viscosity * max_visc_sum));
  }
  if (amax2 > 0) lim.body_force = 0.25 * std::sqrt(hm / std::sqrt(amax2));
  const double kmax = species_.max_diffusivity();
  if (kmax > 0) {
    lim.diffusion = 0.125 * hm * hm / kmax;
    if (max_k_sum > 0) lim.diffusion = std::min(lim.diffusion, 1.0 / (2.0 * kmax * max_k_sum));
  }
  if (species_.has_reactions()) {
    ParticleState shape;
    shape.densities = y.rho;
    const double j = species_.reaction_rate_scale(y.c, shape);
    if (j > 0) lim.reaction = 1.0 / j;
  }
  return lim;
}

void SdpdBackend::evaluate_current(std::uint64_t noise_step, Rates& out) {
  require_initialized("evaluate_current");
  evaluate(y_, noise_step, out, true);
}

StabilityLimits SdpdBackend::current_limits() {
  require_initialized("current_limits");
  evaluate(y_, 0, r0_, false);
  return limits(y_, r0_);
}

StepReport SdpdBackend::step(std::uint64_t step_index, double time_step) {
  const std::size_t n = mass_.size();
  const int dim = model_.box.dimension;
  StepReport rep;
  rep.stable_dt = StabilityLimits::kNone;
  rep.limiting_criterion = "none";
  double remaining = time_step;
  std::uint32_t sub = 0;
  ytmp_.c.resize(y_.c.size());
  const bool fused = fused_ok();
  while (remaining > 0 && fused) {
    const std::uint64_t key = (step_index << 16) | sub;
    bool check = false;
    double dt = 0;
    switch (dim) {
      case 1:
        dt = fused_substep<1>(step_index, key, remaining, sub, rep, check);
        break;
      case 2:
        dt = fused_substep<2>(step_index, key, remaining, sub, rep, check);
        break;
      default:
        dt = fused_substep<3>(step_index, key, remaining, sub, rep, check);
        break;
    }
    remaining -= dt;
    if (remaining < 1e-12 * time_step) remaining = 0;
    time_ += dt;
    ++sub;
    if (check) check_health(step_index, sub);
  }
  while (remaining > 0 && !fused) {
    const std::uint64_t key = (step_index << 16) | sub;
    evaluate(y_, key, r0_, true);
    const auto [dt, lim_dt, lim_name] =
        next_substep(limits(y_, r0_), model_.max_time_step, model_.force_time_step, remaining,
                     rep.stable_dt, rep.limiting_criterion);
    if (sub >= kMaxSubsteps) {
      throw NumericalFailure("sdpd: more than 65535 sub-steps needed in one advance (limit '" +
                                 lim_name + "' = " + format_value(lim_dt) +
                                 "); use a smaller coupling time_step",
                             {{"step", std::to_string(step_index)}, {"limit", lim_name}});
    }
    const double sdt = std::sqrt(dt);
    const bool noise_on = !r0_.acc_noise.empty();
    // Predictor: Y~ = Y + dt f(Y). One parallel pass (copy and update; serial copies limited
    // the two-thread speed-up in 2D, ~12 pairs per particle).
    ytmp_.x.resize(3 * n);
    ytmp_.v.resize(3 * n);
    ytmp_.rho.resize(n);
    const bool continuity = model_.density_mode == DensityMode::kContinuity;
    const auto ni = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static) if (ni > kMinParallelLight)
    for (std::int64_t ii = 0; ii < ni; ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      for (int a = 0; a < 3; ++a) {
        ytmp_.x[3 * i + a] = y_.x[3 * i + a];
        ytmp_.v[3 * i + a] = y_.v[3 * i + a];
      }
      ytmp_.rho[i] = continuity ? y_.rho[i] + dt * r0_.drho[i] : y_.rho[i];
      if (wall_[i]) continue;
      for (int a = 0; a < dim; ++a) {
        const std::size_t k = 3 * i + a;
        ytmp_.x[k] += dt * y_.v[k];
        ytmp_.v[k] += dt * r0_.acc[k] + (noise_on ? sdt * r0_.acc_noise[k] : 0.0);
      }
      pbox_.wrap(&ytmp_.x[3 * i]);
    }
    for (std::size_t s = 0; s < y_.c.size(); ++s) {
      ytmp_.c[s] = y_.c[s];
      if (!model_.species[s].deterministic) continue;
      for (std::size_t i = 0; i < n; ++i) ytmp_.c[s][i] += dt * r0_.dc[s][i];
    }
    evaluate(ytmp_, key, r1_, false);  // noise: the start-of-step force is reused
    // Corrector: Y = Y + dt/2 (f(Y) + f(Y~)), same noise increment.
#pragma omp parallel for schedule(static) if (ni > kMinParallelLight)
    for (std::int64_t ii = 0; ii < ni; ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      // (summation density: rho~ is recomputed at the next evaluation anyway)
      y_.rho[i] = continuity ? y_.rho[i] + 0.5 * dt * (r0_.drho[i] + r1_.drho[i]) : ytmp_.rho[i];
      if (wall_[i]) continue;
      for (int a = 0; a < dim; ++a) {
        const std::size_t k = 3 * i + a;
        y_.x[k] += 0.5 * dt * (y_.v[k] + ytmp_.v[k]);
        y_.v[k] += 0.5 * dt * (r0_.acc[k] + r1_.acc[k]) + (noise_on ? sdt * r0_.acc_noise[k] : 0.0);
      }
      pbox_.wrap(&y_.x[3 * i]);
    }
    for (std::size_t s = 0; s < y_.c.size(); ++s) {
      if (!model_.species[s].deterministic) continue;
      for (std::size_t i = 0; i < n; ++i) y_.c[s][i] += 0.5 * dt * (r0_.dc[s][i] + r1_.dc[s][i]);
    }
    remaining -= dt;
    if (remaining < 1e-12 * time_step) remaining = 0;
    time_ += dt;
    ++sub;
    if (open_) apply_open_boundary(dt);
    check_health(step_index, sub);
  }
  rep.time = time_;
  rep.substeps = sub;
  rep.particles_moved = true;
  rep.min_density = std::numeric_limits<double>::infinity();
  rep.max_density = 0;
  double vmax2 = 0;
  if (fused) {  // (from the last corrector loop)
    rep.min_density = report_rho_min_;
    rep.max_density = report_rho_max_;
    vmax2 = report_vmax2_;
  }
  for (std::size_t i = 0; i < n && !fused; ++i) {
    rep.min_density = std::min(rep.min_density, y_.rho[i]);
    rep.max_density = std::max(rep.max_density, y_.rho[i]);
    if (wall_[i]) continue;
    const double* v = &y_.v[3 * i];
    vmax2 = std::max(vmax2, v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  }
  rep.max_speed = std::sqrt(vmax2);
  return rep;
}

// Open boundary (docs/fluid-core.md 2, "Open boundaries"). The inlet is a conveyor: its slots
// move with the inflow velocity; a conveyor particle entering the fluid leaves a hole one inlet
// length behind it (a hole reaching the fluid moves back by the same length). The outlet
// particles farthest downstream fill the holes (the hole farthest downstream first); with no
// outlet particle left a hole waits. An outlet particle past outlet_hi with no hole to fill is
// shifted back by outlet_hi - inlet_lo (an extra inlet particle, no slot). Kinds follow the
// position along the flow axis. Serial, in index order: independent of the thread count.
void SdpdBackend::apply_open_boundary(double dt) {
  const auto& ob = model_.open_boundary;
  const auto a = static_cast<std::size_t>(ob.axis);
  const std::size_t n = mass_.size();
  const double lb_in = ob.fluid_lo - ob.inlet_lo;
  auto classify = [&](double s) {
    return s < ob.fluid_lo   ? ParticleKind::kInlet
           : s < ob.fluid_hi ? ParticleKind::kFluid
                             : ParticleKind::kOutlet;
  };
  for (std::size_t k = 0; k < holes_.size(); k += 3) {
    double* x = &holes_[k];
    x[a] += dt * ob.inflow_speed(x);
    if (x[a] >= ob.fluid_lo) x[a] -= lb_in;
  }
  ob_outlets_.clear();
  bool past = false;
  for (std::size_t i = 0; i < n; ++i) {
    if (wall_[i]) continue;
    const double* x = &y_.x[3 * i];
    const ParticleKind k = classify(x[a]);
    if (kinds_[i] == ParticleKind::kInlet && k != ParticleKind::kInlet && conveyor_[i]) {
      conveyor_[i] = 0;  // leaves a hole behind it
      holes_.insert(holes_.end(), {x[0], x[1], x[2]});
      holes_[holes_.size() - 3 + a] -= lb_in;
    }
    kinds_[i] = k;
    if (k == ParticleKind::kOutlet) {
      ob_outlets_.push_back(static_cast<std::uint32_t>(i));
      past = past || x[a] > ob.outlet_hi;
    }
  }
  if (!ob_outlets_.empty() && (past || !holes_.empty())) {
    // outlet particles and holes, farthest downstream first (ties: lower index / older hole)
    std::sort(ob_outlets_.begin(), ob_outlets_.end(), [&](std::uint32_t p, std::uint32_t q) {
      const double xp = y_.x[3 * p + a], xq = y_.x[3 * q + a];
      return xp > xq || (xp == xq && p < q);
    });
    ob_crossing_.resize(holes_.size() / 3);
    for (std::size_t k = 0; k < ob_crossing_.size(); ++k)
      ob_crossing_[k] = static_cast<std::uint32_t>(k);
    std::stable_sort(
        ob_crossing_.begin(), ob_crossing_.end(),
        [&](std::uint32_t p, std::uint32_t q) { return holes_[3 * p + a] > holes_[3 * q + a]; });
    const double shift = ob.outlet_hi - ob.inlet_lo;
    const std::size_t filled = std::min(ob_outlets_.size(), ob_crossing_.size());
    for (std::size_t k = 0; k < ob_outlets_.size(); ++k) {
      const std::uint32_t j = ob_outlets_[k];
      if (k < filled) {
        for (int q = 0; q < 3; ++q) y_.x[3 * j + q] = holes_[3 * ob_crossing_[k] + q];
        conveyor_[j] = 1;
        kinds_[j] = ParticleKind::kInlet;
      } else if (y_.x[3 * j + a] > ob.outlet_hi) {
        y_.x[3 * j + a] -= shift;
        conveyor_[j] = 0;  // an extra inlet particle: it leaves no hole
        kinds_[j] = ParticleKind::kInlet;
      } else {
        break;  // (sorted: the others are inside the outlet)
      }
    }
    if (filled > 0) {  // drop the filled holes, keep the others in creation order
      std::vector<std::uint8_t> gone(ob_crossing_.size(), 0);
      for (std::size_t k = 0; k < filled; ++k) gone[ob_crossing_[k]] = 1;
      std::size_t w = 0;
      for (std::size_t k = 0; k < gone.size(); ++k) {
        if (gone[k]) continue;
        for (int q = 0; q < 3; ++q) holes_[3 * w + q] = holes_[3 * k + q];
        ++w;
      }
      holes_.resize(3 * w);
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (wall_[i]) continue;
    buffer_[i] = kinds_[i] != ParticleKind::kFluid;
    if (kinds_[i] == ParticleKind::kInlet) {  // prescribed velocity
      double* vi = &y_.v[3 * i];
      vi[0] = vi[1] = vi[2] = 0.0;
      vi[a] = ob.inflow_speed(&y_.x[3 * i]);
    } else if (kinds_[i] == ParticleKind::kOutlet) {  // prescribed pressure P = 0
      y_.rho[i] = model_.reference_density;
    }
  }
  // Zero-gradient values from the fluid (Lastiwka et al. 2009: a subsonic inlet takes one
  // quantity from inside, the pressure; a subsonic outlet everything but the pressure): the
  // density of an inlet particle and the velocity of an outlet particle are the Shepard average,
  // over the fluid particles within one kernel support of the buffer's face, weighted by the
  // kernel of the cross-flow distance (so d/d(axis) = 0 across the buffer).
  const double h = kernel_.support();
  extrapolate_from_fluid(ParticleKind::kInlet, ob.fluid_lo, ob.fluid_lo + h);
  extrapolate_from_fluid(ParticleKind::kOutlet, ob.fluid_hi - h, ob.fluid_hi);
  // Reactions fire by kind: their sites move with the particles' new kinds.
  if (species_.has_reactions()) species_.update_sites(kinds_);
}

void SdpdBackend::extrapolate_from_fluid(ParticleKind target, double lo, double hi) {
  const auto& ob = model_.open_boundary;
  const auto a = static_cast<std::size_t>(ob.axis);
  const std::size_t n = mass_.size();
  const double h = kernel_.support(), h2 = h * h;
  slab_fluid_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    const double s = y_.x[3 * i + a];
    if (kinds_[i] == ParticleKind::kFluid && s >= lo && s < hi)
      slab_fluid_.push_back(static_cast<std::uint32_t>(i));
  }
  const int dim = model_.box.dimension;
  const bool velocity = target == ParticleKind::kOutlet;
  for (std::size_t i = 0; i < n; ++i) {
    if (kinds_[i] != target) continue;
    double wsum = 0, v[3] = {0, 0, 0}, rho = 0;
    for (const std::uint32_t j : slab_fluid_) {
      double d[3] = {0, 0, 0};
      for (int c = 0; c < dim; ++c) {
        if (c != ob.axis) d[c] = y_.x[3 * i + c] - y_.x[3 * j + c];
      }
      pbox_.minimum_image(d);
      const double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
      if (r2 >= h2) continue;
      const double w = kernel_.w(std::sqrt(r2)) * mass_[j] / y_.rho[j];
      wsum += w;
      for (int c = 0; c < 3; ++c) v[c] += w * y_.v[3 * j + c];
      rho += w * y_.rho[j];
    }
    if (!(wsum > 0)) continue;  // no fluid across from it: keeps its values
    if (velocity) {
      for (int c = 0; c < 3; ++c) y_.v[3 * i + c] = v[c] / wsum;
    } else {
      y_.rho[i] = rho / wsum;
    }
  }
}

void SdpdBackend::check_health(std::uint64_t step_index, std::uint32_t substep) const {
  HealthView h{y_.x, y_.v, y_.c, model_.species, ids_, pbox_};
  h.rho = &y_.rho;
  h.rho0 = model_.reference_density;
  h.band = model_.density_band;
  fluid::check_health(name(), h, step_index, substep);
}

std::size_t SdpdBackend::memory_bytes() const {
  auto vb = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
  auto yb = [&](const Y& y) {
    std::size_t b = vb(y.x) + vb(y.v) + vb(y.rho);
    for (const auto& c : y.c) b += vb(c);
    return b;
  };
  auto rb = [&](const Rates& r) {
    std::size_t b = vb(r.acc) + vb(r.acc_noise) + vb(r.drho);
    for (const auto& c : r.dc) b += vb(c);
    return b;
  };
  std::size_t noise_bytes = 0;
  for (const auto& b : scratch_) noise_bytes += b.bytes();
  return yb(y_) + yb(ytmp_) + rb(r0_) + rb(r1_) + vb(nlist_.offsets) + vb(nlist_.indices) +
         vb(list_ref_x_) + vb(wall_) + vb(wall_region_) + vb(wall_depth_) + vb(mass_) + vb(kinds_) +
         vb(ids_) + vb(pd2_) + vb(inv_nd_) + vb(vol_) + vb(sqrt_inv_nd_) + noise_bytes +
         vb(slab_of_) + vb(slab_start_) + vb(slab_members_) + vb(hin_) + vb(hacc_);
}

void SdpdBackend::write_state(ParticleState& out) const {
  out.dimension = model_.box.dimension;
  out.positions = y_.x;
  out.velocities = y_.v;
  out.densities = y_.rho;
  out.masses = mass_;
  out.kinds = kinds_;
  out.ids = ids_;
}

void SdpdBackend::save_state(BlobWriter& w) const {
  w.put(model_.seed);
  w.put(time_);
  w.put_vector(y_.x);
  w.put_vector(y_.v);
  w.put_vector(y_.rho);
  w.put<std::uint64_t>(y_.c.size());
  for (const auto& c : y_.c) w.put_vector(c);
  // The half-pair path sums in slab order, and slabs are assigned at list builds: restoring the
  // list at the same reference positions keeps restarts bit-exact.
  w.put_vector(list_ref_x_);
  if (open_) {  // version 3: kinds change at open boundaries
    std::vector<std::uint8_t> k(kinds_.size());
    for (std::size_t i = 0; i < k.size(); ++i) k[i] = static_cast<std::uint8_t>(kinds_[i]);
    w.put_vector(k);
    w.put_vector(conveyor_);
    w.put_vector(holes_);
  }
}

void SdpdBackend::restore_state(BlobReader& r, std::uint32_t version) {
  constexpr std::uint32_t kBlobVersionOpen = 3;
  if (version < 1 || version > kBlobVersionOpen) {
    throw InvalidArgument("restore: blob version " + std::to_string(version) +
                          " unsupported (this build reads 1, 2 and 3)");
  }
  if ((version == kBlobVersionOpen) != open_) {
    throw InvalidArgument(std::string("restore: blob ") +
                          (open_ ? "has no particle kinds but the model has an open boundary"
                                 : "has particle kinds (open boundary) but the model has none"));
  }
  if (r.get<std::uint64_t>() != model_.seed)
    throw InvalidArgument("restore: blob seed differs from the model seed");
  const std::size_t n = mass_.size();
  Y y;
  const double t = r.get<double>();
  y.x = r.get_vector<double>(3 * n);
  y.v = r.get_vector<double>(3 * n);
  y.rho = r.get_vector<double>(n);
  const auto ns = r.get<std::uint64_t>();
  if (ns != y_.c.size())
    throw InvalidArgument("restore: blob has " + std::to_string(ns) + " species, model has " +
                          std::to_string(y_.c.size()));
  for (std::size_t s = 0; s < ns; ++s) y.c.push_back(r.get_vector<double>(n));
  std::vector<double> ref;
  if (version >= 2) {
    ref = r.get_vector<double>();
    if (!ref.empty() && ref.size() != 3 * n)
      throw InvalidArgument("restore: list reference positions have the wrong size");
  }
  std::vector<ParticleKind> kinds = kinds_;
  std::vector<std::uint8_t> conveyor = conveyor_;
  std::vector<double> holes = holes_;
  if (version == kBlobVersionOpen) {
    const auto k = r.get_vector<std::uint8_t>(n);
    for (std::size_t i = 0; i < n; ++i) {
      const bool wall_k = k[i] == static_cast<std::uint8_t>(ParticleKind::kWall);
      if (k[i] > 3 || wall_k != (wall_[i] != 0))
        throw InvalidArgument("restore: particle kinds do not match the model's wall particles");
      kinds[i] = static_cast<ParticleKind>(k[i]);
    }
    conveyor = r.get_vector<std::uint8_t>(n);
    holes = r.get_vector<double>();
    if (holes.size() % 3 != 0) throw InvalidArgument("restore: inlet holes have the wrong size");
  }
  r.expect_end();
  y_ = std::move(y);
  kinds_ = std::move(kinds);
  conveyor_ = std::move(conveyor);
  holes_ = std::move(holes);
  for (std::size_t i = 0; i < n; ++i) {
    buffer_[i] = kinds_[i] == ParticleKind::kInlet || kinds_[i] == ParticleKind::kOutlet;
  }
  if (open_ && species_.has_reactions()) species_.update_sites(kinds_);
  time_ = t;
  prepared_ = false;
  list_ref_x_.clear();
  if (!ref.empty()) rebuild_neighbors(ref);
}

}  // namespace sadr::fluid
