// SPDX-License-Identifier: MIT
/// \file sdpd_backend.cpp
/// SdpdBackend: setup, the neighbour lists and the slabs, the evaluation dispatch, memory.
#include "sdpd_backend.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "sadr/common/status.hpp"
#include "sadr/fluid/parallel.hpp"

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

struct TransportVelocitySettings {
  bool on = false;
  double pressure = 5.0;  ///< p_b / (rho_0 c_0^2), the paper's background pressure
};

/// The backend's own parameters (sdpd_schema.cpp): transport_velocity (0 off, 1 on) and
/// shift_pressure; any other name is refused.
TransportVelocitySettings transport_velocity_settings(const FluidModel& model) {
  TransportVelocitySettings t;
  for (const auto& [key, value] : model.backend_parameters) {
    if (key == "transport_velocity" && (value == 0.0 || value == 1.0)) {
      t.on = value == 1.0;
    } else if (key == "shift_pressure" && std::isfinite(value) && value >= 0.0) {
      t.pressure = value;
    } else if (key == "transport_velocity" || key == "shift_pressure") {
      throw InvalidArgument("sdpd: " + key + " = " + format_value(value) +
                            (key == "transport_velocity" ? " (allowed: 0 off, 1 on)"
                                                         : " (allowed: a finite number >= 0)"));
    } else {
      throw InvalidArgument("sdpd: unknown parameter '" + key +
                            "' (this backend takes none beyond density_diffusion, diffusion_eps, "
                            "density_band, neighbor_skin, transport_velocity, "
                            "shift_pressure)");
    }
  }
  if (t.on && model.open_boundary.enabled) {
    throw InvalidArgument(
        "sdpd: transport_velocity = on is not available with an open boundary (the buffers "
        "move with the velocity)");
  }
  return t;
}
}  // namespace

void SdpdBackend::setup(const FluidModel& model, const ParticleState& initial,
                        const std::vector<std::vector<double>>& concentrations) {
  check_initial(model, initial);
  const TransportVelocitySettings tvf = transport_velocity_settings(model);
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
  morris_.setup(model, initial);
  ids_ = initial.ids;
  if (ids_.empty()) {
    ids_.resize(n);
    for (std::size_t i = 0; i < n; ++i) ids_[i] = i;
  }
  y_.x = initial.positions;
  for (std::size_t i = 0; i < n; ++i) pbox_.wrap(&y_.x[3 * i]);
  y_.v = initial.velocities.empty() ? std::vector<double>(3 * n, 0.0) : initial.velocities;
  for (std::size_t i = 0; i < n; ++i) {
    // a wall particle's velocity is its prescribed one (moving walls; never integrated)
    for (int a = dim; a < 3; ++a) y_.v[3 * i + a] = 0.0;
  }
  y_.rho = initial.densities;
  y_.c.assign(model.species.size(), std::vector<double>(n, 0.0));
  for (std::size_t s = 0; s < concentrations.size(); ++s) y_.c[s] = concentrations[s];
  species_.setup(model_, initial);
  species_.apply_dirichlet(y_.c);
  list_ref_x_.clear();
  nlist_ = {};
  open_.setup(model, kernel_, pbox_, y_.x, wall_, kinds_);
  tvf_ = tvf.on;
  adami_ = model.wall_model == WallModel::kAdami;
  adami_p_.clear();
  adami_v_.clear();
  adami_surfaces();
  tvf_shift_pressure_ =
      tvf.pressure * model.reference_density * model.sound_speed * model.sound_speed;
  half_ok_ = !tvf_ && !open_.enabled() && !morris_.enabled() && species_.transported().empty() &&
             !species_.has_reactions() &&
             std::none_of(wall_.begin(), wall_.end(), [](std::uint8_t w) { return w != 0; });
  if (open_.enabled()) apply_open_boundary(0.0);  // (reaction sites follow the kinds it sets)
  setup_bodies();
  setup_moving_bodies();
  time_ = 0;
  prepared_ = false;
}

void SdpdBackend::apply_open_boundary(double dt) {
  open_.apply(dt, {y_.x, y_.v, y_.rho, kinds_, mass_, wall_});
  // Reactions fire by kind: their sites move with the particles' new kinds.
  if (species_.has_reactions()) species_.update_sites(kinds_);
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

void SdpdBackend::rebuild_neighbors(const std::vector<double>& x) {
  builder_->build(x, nlist_);
  ++list_builds_;
  list_ref_x_ = x;
  // Half path: slabs along the last active axis; the list keeps its forward pairs only. The
  // slabs depend on the positions at the list build, which are saved (exact restarts).
  if (half_ok_) {
    slabs_.partition_and_filter(pbox_, model_.box.dimension - 1, builder_->cutoff(), x, nlist_);
  }
}

void SdpdBackend::evaluate(Y& y, std::uint64_t noise_step, Rates& out, bool with_noise) {
  prepared_ = false;  // hin_/hacc_ are reused by the half path
  const bool noise_on = with_noise && model_.temperature > 0;
  ensure_neighbors(y.x);
  switch (model_.box.dimension) {
    case 1:
      half_ok_ ? evaluate_half<1>(y, noise_step, out, noise_on)
               : evaluate_gather<1>(y, noise_step, out, noise_on);
      break;
    case 2:
      half_ok_ ? evaluate_half<2>(y, noise_step, out, noise_on)
               : evaluate_gather<2>(y, noise_step, out, noise_on);
      break;
    default:
      half_ok_ ? evaluate_half<3>(y, noise_step, out, noise_on)
               : evaluate_gather<3>(y, noise_step, out, noise_on);
      break;
  }
}

void SdpdBackend::evaluate_current(std::uint64_t noise_step, Rates& out) {
  require_initialized("evaluate_current");
  evaluate(y_, noise_step, out, true);
}

void SdpdBackend::evaluate_current(std::uint64_t noise_step, double dt, Rates& out) {
  evaluate_current(noise_step, out);
  if (tvf_) apply_transport_velocity(y_, dt, out);
}

std::size_t SdpdBackend::memory_bytes() const {
  auto vb = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
  auto yb = [&](const Y& y) {
    std::size_t b = vb(y.x) + vb(y.v) + vb(y.rho);
    for (const auto& c : y.c) b += vb(c);
    return b;
  };
  auto rb = [&](const Rates& r) {
    std::size_t b = vb(r.acc) + vb(r.acc_noise) + vb(r.drho) + vb(r.shift);
    for (const auto& c : r.dc) b += vb(c);
    return b;
  };
  std::size_t noise_bytes = 0;
  for (const auto& b : scratch_) noise_bytes += b.bytes();
  return yb(y_) + yb(ytmp_) + rb(r0_) + rb(r1_) + vb(nlist_.offsets) + vb(nlist_.indices) +
         vb(list_ref_x_) + vb(wall_) + morris_.bytes() + open_.bytes() + vb(mass_) + vb(kinds_) +
         vb(ids_) + vb(pd2_) + vb(inv_nd_) + vb(vol_) + vb(sqrt_inv_nd_) + noise_bytes +
         vb(adami_p_) + vb(adami_v_) + vb(adami_tangent_) + vb(adami_kappa_) + slabs_.bytes() +
         vb(hin_) + vb(hacc_) + vb(moving_.of) + vb(moving_.particle) + vb(moving_.body) +
         vb(moving_.x0) + vb(moving_.tangent) + vb(moving_.tangent_body) + vb(moving_.n0);
}

void register_sdpd_backend(BackendRegistry& registry) {
  registry.add("sdpd", [] { return std::make_unique<SdpdBackend>(); });
}

}  // namespace sadr::fluid
