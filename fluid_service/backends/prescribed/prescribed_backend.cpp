// SPDX-License-Identifier: MIT
#include "prescribed_backend.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "sadr/common/status.hpp"

namespace sadr::fluid {

PrescribedField PrescribedField::from_model(const FluidModel& model, bool& rk4) {
  const auto& p = model.backend_parameters;
  PrescribedField f;
  rk4 = false;
  for (const auto& entry : p) {
    // Not a structured binding: clang 14 (preset fuzz) cannot capture one in the lambda below.
    const std::string& key = entry.first;
    const double v = entry.second;
    if (!std::isfinite(v)) {
      throw InvalidArgument("prescribed." + key + " = " + format_value(v) + " (must be finite)");
    }
    auto whole = [&](int hi) {
      if (!(v >= 0 && v <= hi && v == std::floor(v))) {
        throw InvalidArgument("prescribed." + key + " = " + format_value(v) +
                              " (allowed: a whole number in [0, " + std::to_string(hi) + "])");
      }
      return static_cast<int>(v);
    };
    if (key == "field") {
      f.kind = static_cast<Kind>(whole(4));
    } else if (key == "integrator") {
      rk4 = whole(1) == 1;
    } else if (key == "ux" || key == "uy" || key == "uz") {
      f.u[static_cast<std::size_t>(key[1] - 'x')] = v;
    } else if (key == "shear_rate") {
      f.shear_rate = v;
    } else if (key == "y0") {
      f.y0 = v;
    } else if (key == "max_velocity") {
      f.max_velocity = v;
    } else if (key == "wall_lo") {
      f.wall_lo = v;
    } else if (key == "wall_hi") {
      f.wall_hi = v;
    } else if (key == "omega") {
      f.omega = v;
    } else if (key == "cx") {
      f.cx = v;
    } else if (key == "cy") {
      f.cy = v;
    } else {
      throw InvalidArgument("prescribed: unknown parameter '" + key +
                            "' (known: field, integrator, ux, uy, uz, shear_rate, y0, "
                            "max_velocity, wall_lo, wall_hi, omega, cx, cy)");
    }
  }
  for (const auto& entry : model.backend_files) {
    if (entry.first != "field_file") {
      throw InvalidArgument("prescribed: unknown file parameter '" + entry.first +
                            "' (known: field_file)");
    }
    if (f.kind != Kind::kGrid) {
      throw InvalidArgument("prescribed: field_file applies to field csv only (field is " +
                            std::to_string(static_cast<int>(f.kind)) + ")");
    }
  }
  if (f.kind == Kind::kGrid) {
    const auto file = model.backend_files.find("field_file");
    if (file == model.backend_files.end()) {
      throw InvalidArgument("prescribed: field csv needs field_file (the CSV of the grid)");
    }
    if (!rk4) {
      throw InvalidArgument(
          "prescribed: field csv needs integrator rk4 (an interpolated field has no closed-form "
          "flow map)");
    }
    f.grid = std::make_shared<const GridField>(GridField::read(file->second, model.box));
  }
  if (f.kind == Kind::kPoiseuille && !(f.wall_hi > f.wall_lo)) {
    throw InvalidArgument("prescribed: wall_hi = " + format_value(f.wall_hi) +
                          " must exceed wall_lo = " + format_value(f.wall_lo));
  }
  return f;
}

void PrescribedField::velocity(const double* x, double* v) const {
  v[0] = v[1] = v[2] = 0.0;
  switch (kind) {
    case Kind::kUniform:
      for (int a = 0; a < 3; ++a) v[a] = u[static_cast<std::size_t>(a)];
      break;
    case Kind::kShear:
      v[0] = shear_rate * (x[1] - y0);
      break;
    case Kind::kPoiseuille: {
      const double w = wall_hi - wall_lo;
      if (x[1] > wall_lo && x[1] < wall_hi)
        v[0] = 4.0 * max_velocity * (x[1] - wall_lo) * (wall_hi - x[1]) / (w * w);
      break;
    }
    case Kind::kRotation:
      v[0] = -omega * (x[1] - cy);
      v[1] = omega * (x[0] - cx);
      break;
    case Kind::kGrid:
      if (!grid->velocity(x, v)) {
        throw Error(StatusCode::kOutOfRange,
                    "at " + grid->point(x) + " lies outside the field's grid " + grid->extent() +
                        " (" + grid->path() +
                        "); a grid must cover every position the fluid particles reach",
                    {{"field", "position"}, {"file", grid->path()}});
      }
      break;
  }
}

void PrescribedField::exact(double* x, double dt) const {
  if (kind == Kind::kRotation) {  // rotation by omega dt about (cx, cy)
    const double c = std::cos(omega * dt), s = std::sin(omega * dt);
    const double dx = x[0] - cx, dy = x[1] - cy;
    x[0] = cx + c * dx - s * dy;
    x[1] = cy + s * dx + c * dy;
    return;
  }
  double v[3];  // the other fields are constant along their streamlines
  velocity(x, v);
  for (int a = 0; a < 3; ++a) x[a] += dt * v[a];
}

void PrescribedField::rk4(double* x, double dt) const {
  double k1[3], k2[3], k3[3], k4[3], y[3];
  velocity(x, k1);
  for (int a = 0; a < 3; ++a) y[a] = x[a] + 0.5 * dt * k1[a];
  velocity(y, k2);
  for (int a = 0; a < 3; ++a) y[a] = x[a] + 0.5 * dt * k2[a];
  velocity(y, k3);
  for (int a = 0; a < 3; ++a) y[a] = x[a] + dt * k3[a];
  velocity(y, k4);
  for (int a = 0; a < 3; ++a) x[a] += dt / 6.0 * (k1[a] + 2.0 * k2[a] + 2.0 * k3[a] + k4[a]);
}

void PrescribedBackend::setup(const FluidModel& model, const ParticleState& initial,
                              const std::vector<std::vector<double>>& concentrations) {
  field_ = PrescribedField::from_model(model, rk4_);
  model_ = model;
  pbox_ = PeriodicBox(model.box);
  state_ = initial;
  const std::size_t n = state_.size();
  if (state_.kinds.empty()) state_.kinds.assign(n, ParticleKind::kFluid);
  if (state_.ids.empty()) {
    state_.ids.resize(n);
    for (std::size_t i = 0; i < n; ++i) state_.ids[i] = i;
  }
  state_.velocities.assign(3 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    pbox_.wrap(&state_.positions[3 * i]);
    if (state_.kind(i) != ParticleKind::kWall) set_velocity(i);
  }
  for (std::size_t i = 0; i < n; ++i) {
    for (int a = model.box.dimension; a < 3; ++a) state_.velocities[3 * i + a] = 0.0;
  }
  c_.assign(model.species.size(), std::vector<double>(n, 0.0));
  for (std::size_t s = 0; s < concentrations.size(); ++s) c_[s] = concentrations[s];
  species_.setup(model_, state_);
  species_.transport().apply_dirichlet(c_);
  species_.reset_scratch(c_);
  time_ = 0;
}

void PrescribedBackend::set_velocity(std::size_t i) {
  try {
    field_.velocity(&state_.positions[3 * i], &state_.velocities[3 * i]);
  } catch (const Error& e) {
    if (e.code() != StatusCode::kOutOfRange) throw;
    throw InvalidArgument("prescribed: particle " + std::to_string(state_.ids[i]) + " " + e.what(),
                          e.details());
  }
}

void PrescribedBackend::move(double dt) {
  const std::size_t n = state_.size();
  const int dim = model_.box.dimension;
  for (std::size_t i = 0; i < n; ++i) {
    if (state_.kind(i) == ParticleKind::kWall) continue;
    double* x = &state_.positions[3 * i];
    const double x0[3] = {x[0], x[1], x[2]};
    try {
      if (rk4_) {
        field_.rk4(x, dt);
      } else {
        field_.exact(x, dt);
      }
      for (int a = dim; a < 3; ++a) x[a] = x0[a];  // inactive axes stay put
      pbox_.wrap(x);
      field_.velocity(x, &state_.velocities[3 * i]);
    } catch (const Error& e) {
      if (e.code() != StatusCode::kOutOfRange) throw;
      throw Error(StatusCode::kOutOfRange,
                  "prescribed: at step " + std::to_string(step_) + " particle " +
                      std::to_string(state_.ids[i]) + " (from " + format_value(x0[0]) + ", " +
                      format_value(x0[1]) + ") " + e.what(),
                  e.details());
    }
    for (int a = dim; a < 3; ++a) state_.velocities[3 * i + a] = 0.0;
  }
}

SubstepBound PrescribedBackend::current_substep_bound() {
  require_initialized("current_substep_bound");
  if (species_.active()) {
    return substep_bound(species_.limits(c_, state_), model_.max_time_step, model_.force_time_step);
  }
  SubstepBound b;
  if (rk4_ && model_.max_time_step > 0) {
    b.dt = model_.max_time_step;
    b.criterion = "max_time_step";
  }
  return b;
}

StepReport PrescribedBackend::step(std::uint64_t step_index, double time_step) {
  step_ = step_index;
  StepReport rep;
  rep.stable_dt = StabilityLimits::kNone;
  rep.limiting_criterion = "none";
  // Advection: the exact map in one piece, RK4 in the fewest equal sub-steps <= max_time_step.
  std::uint32_t moves = 1;
  if (rk4_ && model_.max_time_step > 0) {
    moves = static_cast<std::uint32_t>(
        std::max(1.0, std::ceil(time_step / model_.max_time_step * (1.0 - 1e-12))));
  }
  for (std::uint32_t k = 0; k < moves; ++k) move(time_step / moves);
  HealthView h{state_.positions, state_.velocities, c_, model_.species, state_.ids, pbox_};
  check_health(name(), h, step_index, moves);
  // Species at the new positions (Lie splitting; the operator's own adaptive sub-steps).
  std::uint32_t sub = moves;
  double t = time_;
  if (species_.active()) {
    species_.build(state_);
    sub = std::max(sub, species_.advance(name(), state_, c_, step_index, time_step, t, rep));
  }
  time_ += time_step;
  rep.time = time_;
  rep.substeps = sub;
  rep.particles_moved = true;
  double vmax2 = 0;
  for (std::size_t i = 0; i < state_.size(); ++i) {
    const double* v = &state_.velocities[3 * i];
    vmax2 = std::max(vmax2, v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  }
  rep.max_speed = std::sqrt(vmax2);
  rep.set_density_band(state_.densities);
  return rep;
}

void PrescribedBackend::save_state(BlobWriter& w) const {
  w.put(time_);
  w.put_vector(state_.positions);
  w.put<std::uint64_t>(c_.size());
  for (const auto& c : c_) w.put_vector(c);
}

void PrescribedBackend::restore_state(BlobReader& r, std::uint32_t version) {
  if (version != 1)
    throw InvalidArgument("restore: blob version " + std::to_string(version) + " unsupported");
  const double t = r.get<double>();
  auto x = r.get_vector<double>(state_.positions.size());
  const auto ns = r.get<std::uint64_t>();
  if (ns != c_.size()) throw InvalidArgument("restore: species count differs from the model");
  std::vector<std::vector<double>> c;
  for (std::size_t s = 0; s < ns; ++s) c.push_back(r.get_vector<double>(state_.size()));
  r.expect_end();
  time_ = t;
  state_.positions = std::move(x);
  for (std::size_t i = 0; i < state_.size(); ++i) {
    if (state_.kind(i) == ParticleKind::kWall) continue;
    set_velocity(i);
    for (int a = model_.box.dimension; a < 3; ++a) state_.velocities[3 * i + a] = 0.0;
  }
  c_ = std::move(c);
}

void register_prescribed_backend(BackendRegistry& registry) {
  registry.add("prescribed", [] { return std::make_unique<PrescribedBackend>(); });
}

}  // namespace sadr::fluid
