// SPDX-License-Identifier: MIT
#include "sadr/fluid/backend_base.hpp"

#include <algorithm>
#include <cmath>

#include "sadr/common/status.hpp"
#include "sadr/fluid/parallel.hpp"

namespace sadr::fluid {

namespace {
constexpr std::string_view kBlobTag = "sadr.fluid.state";
constexpr std::uint32_t kBlobFormat = 1;
// Headers written before the core owned them (state after them unchanged).
constexpr std::uint64_t kLegacySdpdTag = 0x3144504453524441ULL;
constexpr std::uint64_t kLegacyStaticTag = 0x3154415453524441ULL;
constexpr std::string_view kLegacyTdpdTag = "sadr.tdpd";

std::string prefix(std::string_view backend) {
  return std::string(backend) + ": ";
}
}  // namespace

void validate_initial_state(std::string_view backend, const FluidModel& model,
                            const ParticleState& s, const std::vector<std::vector<double>>& c) {
  s.validate();
  const std::string p = prefix(backend);
  if (s.dimension != model.box.dimension) {
    throw InvalidArgument(p + "particle state dimension " + std::to_string(s.dimension) +
                          " differs from box.dimension " + std::to_string(model.box.dimension));
  }
  if (s.size() == 0) throw InvalidArgument(p + "particle state is empty");
  if (s.size() > 0xFFFFFFF0ULL) throw InvalidArgument(p + "too many particles (max 2^32 - 16)");
  if (!c.empty() && c.size() != model.species.size()) {
    throw InvalidArgument(p + "concentrations has " + std::to_string(c.size()) +
                          " species, model has " + std::to_string(model.species.size()));
  }
  for (std::size_t k = 0; k < c.size(); ++k) {
    if (c[k].size() != s.size()) {
      throw InvalidArgument(p + "concentrations[" + std::to_string(k) + "] has " +
                            std::to_string(c[k].size()) + " entries, expected " +
                            std::to_string(s.size()));
    }
    for (std::size_t i = 0; i < c[k].size(); ++i) {
      if (!std::isfinite(c[k][i])) {
        throw InvalidArgument(p + "concentrations[" + std::to_string(k) + "][" + std::to_string(i) +
                              "] = " + format_value(c[k][i]) + " (must be finite)");
      }
    }
  }
}

void validate_advance(std::string_view backend, std::uint64_t step_index, double time_step) {
  if (!(std::isfinite(time_step) && time_step > 0)) {
    throw InvalidArgument(prefix(backend) + "time_step = " + format_value(time_step) +
                          " (must be finite and > 0)");
  }
  if (step_index >= (1ULL << 32))
    throw InvalidArgument(prefix(backend) + "step_index must be < 2^32");
}

void throw_numerical_failure(const HealthFailure& f) {
  const std::string value = format_value(f.value);
  throw NumericalFailure(std::string(f.backend) + " blow-up at step " + std::to_string(f.step) +
                             " sub-step " + std::to_string(f.substep) + ": particle id " +
                             std::to_string(f.particle_id) + " " + f.field + " = " + value + " (" +
                             f.limit + ")",
                         {{"step", std::to_string(f.step)},
                          {"substep", std::to_string(f.substep)},
                          {"particle_id", std::to_string(f.particle_id)},
                          {"field", f.field},
                          {"value", value},
                          {"limit", f.limit}});
}

void check_health(std::string_view backend, const HealthView& h, std::uint64_t step,
                  std::uint32_t substep) {
  const std::size_t n = h.x.size() / 3;
  auto species_ok = [&](std::size_t s, std::size_t i) { return std::isfinite(h.c[s][i]); };
  auto bad = [&](std::size_t i) {
    bool ok = h.box.inside(&h.x[3 * i]);
    for (int a = 0; a < 3; ++a)
      ok = ok && std::isfinite(h.x[3 * i + a]) && std::isfinite(h.v[3 * i + a]);
    if (h.rho) ok = ok && std::fabs((*h.rho)[i] / h.rho0 - 1.0) <= h.band;
    if (h.only_species) {
      for (const int s : *h.only_species) ok = ok && species_ok(static_cast<std::size_t>(s), i);
    } else {
      for (std::size_t s = 0; s < h.c.size(); ++s) ok = ok && species_ok(s, i);
    }
    return !ok;
  };
  const auto ni = static_cast<std::int64_t>(n);
  std::int64_t first = ni;
#pragma omp parallel for schedule(static) if (ni > kMinParallelLight) reduction(min : first)
  for (std::int64_t ii = 0; ii < ni; ++ii) {
    if (bad(static_cast<std::size_t>(ii))) first = std::min(first, ii);
  }
  if (first == ni) return;
  const auto i = static_cast<std::size_t>(first);
  HealthFailure f{backend, step, substep, h.ids.empty() ? i : h.ids[i], {}, 0.0, "non-finite"};
  auto fail = [&](std::string field, double value, std::string limit) {
    f.field = std::move(field);
    f.value = value;
    f.limit = std::move(limit);
    throw_numerical_failure(f);
  };
  constexpr const char* kAxis[3] = {"[0]", "[1]", "[2]"};
  for (int a = 0; a < 3; ++a) {
    const std::string px = std::string("position") + kAxis[a],
                      vx = std::string("velocity") + kAxis[a];
    if (!std::isfinite(h.x[3 * i + a])) fail(px, h.x[3 * i + a], "non-finite");
    if (!std::isfinite(h.v[3 * i + a])) fail(vx, h.v[3 * i + a], "non-finite");
  }
  if (h.rho) {
    const double rho = (*h.rho)[i];
    if (!std::isfinite(rho)) fail("density", rho, "non-finite");
    if (std::fabs(rho / h.rho0 - 1.0) > h.band) {
      fail("density", rho, "outside rho_0 (1 +- " + format_value(h.band) + ")");
    }
  }
  const Box& box = h.box.box();
  for (int a = 0; a < box.dimension; ++a) {
    const double xa = h.x[3 * i + static_cast<std::size_t>(a)];
    if (!box.periodic[a] && (xa < box.lo[a] || xa > box.hi[a])) {
      fail(std::string("position") + kAxis[a], xa,
           "left the box [" + format_value(box.lo[a]) + ", " + format_value(box.hi[a]) +
               "] on a walled axis");
    }
  }
  for (std::size_t s = 0; s < h.c.size(); ++s) {
    if (!species_ok(s, i))
      fail("concentration[" + h.species[s].def.name + "]", h.c[s][i], "non-finite");
  }
}

void write_blob_header(BlobWriter& w, std::string_view backend, std::uint32_t version) {
  w.put_string(kBlobTag);
  w.put(kBlobFormat);
  w.put_string(backend);
  w.put(version);
}

std::uint32_t read_blob_header(BlobReader& r, std::string_view backend) {
  auto expect_backend = [&](const std::string& written) {
    if (written != backend) {
      // The name comes from the blob: echo at most 40 printable ASCII characters (raw
      // bytes made the reply's Status invalid UTF-8, so the client could not parse the
      // reply and lost the message; found by fuzz_fluid_restore).
      std::string shown;
      for (char ch : written.substr(0, 40)) shown += (ch >= 0x20 && ch < 0x7f) ? ch : '?';
      if (written.size() > 40) shown += "... (" + std::to_string(written.size()) + " bytes)";
      throw InvalidArgument("restore: blob was written by backend '" + shown + "', not '" +
                            std::string(backend) + "'");
    }
  };
  const auto tag = r.get<std::uint64_t>();
  if (tag == kLegacySdpdTag || tag == kLegacyStaticTag) {
    const auto version = r.get<std::uint32_t>();
    expect_backend(r.get_string());
    return version;
  }
  if (tag == kLegacyTdpdTag.size() && r.get_chars(tag) == kLegacyTdpdTag) {
    const auto version = r.get<std::uint32_t>();
    expect_backend("tdpd");
    return version;
  }
  if (tag != kBlobTag.size() || r.get_chars(tag) != kBlobTag)
    throw InvalidArgument("restore: not a sadr fluid state blob");
  const auto format = r.get<std::uint32_t>();
  if (format != kBlobFormat) {
    throw InvalidArgument("restore: blob header format " + std::to_string(format) +
                          " unsupported (this build reads " + std::to_string(kBlobFormat) + ")");
  }
  expect_backend(r.get_string());
  return r.get<std::uint32_t>();
}

void BackendBase::require_initialized(const char* what) const {
  if (!initialized_) {
    throw FailedPrecondition(std::string(name()) + ": " + what + " before initialize()");
  }
}

void BackendBase::initialize(const FluidModel& model, const ParticleState& initial,
                             const std::vector<std::vector<double>>& concentrations) {
  check_model(model);
  // The wall model is one the backend's schema entry offers (the scene loader checks the same).
  const auto& walls = capabilities().wall_models;
  const std::string wall = wall_model_name(model.wall_model);
  if (std::find(walls.begin(), walls.end(), wall) == walls.end()) {
    std::string allowed;
    for (const auto& w : walls) allowed += (allowed.empty() ? "" : ", ") + w;
    throw InvalidArgument(prefix(name()) + "wall_model " + wall +
                          " is not offered (allowed: " + allowed + ")");
  }
  if (!model.body_forces.empty() && !capabilities().body_forces) {
    throw InvalidArgument(prefix(name()) + "body_forces ('" + model.body_forces.front().name +
                          "', ...) are not computed by this backend (allowed: none; backend "
                          "sdpd computes them)");
  }
  if (!model.moving_bodies.empty() && !capabilities().moving_walls) {
    throw InvalidArgument(prefix(name()) + "moving_bodies ('" + model.moving_bodies.front().name +
                          "', ...): this backend keeps wall particles at rest (allowed: none; "
                          "backend sdpd moves bodies)");
  }
  validate_initial_state(name(), model, initial, concentrations);
  initialized_ = false;
  setup(model, initial, concentrations);
  initialized_ = true;
}

StepReport BackendBase::advance(std::uint64_t step_index, double time_step) {
  require_initialized("advance");
  validate_advance(name(), step_index, time_step);
  return step(step_index, time_step);
}

void BackendBase::read_state(ParticleState& out) const {
  require_initialized("read_state");
  write_state(out);
}

const std::vector<double>& BackendBase::concentrations(int species) const {
  require_initialized("concentrations");
  const auto& c = fields();
  if (species < 0 || species >= static_cast<int>(c.size())) {
    throw InvalidArgument(prefix(name()) + "species index " + std::to_string(species) +
                          " out of range [0, " + std::to_string(c.size()) + ")");
  }
  return c[static_cast<std::size_t>(species)];
}

void BackendBase::set_concentrations(int species, std::span<const double> values) {
  const std::size_t n = concentrations(species).size();
  if (values.size() != n) {
    throw InvalidArgument(prefix(name()) + "set_concentrations: " + std::to_string(values.size()) +
                          " values, expected " + std::to_string(n));
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      throw InvalidArgument(prefix(name()) + "set_concentrations: value[" + std::to_string(i) +
                            "] = " + format_value(values[i]) + " (must be finite)");
    }
  }
  auto& c = fields();
  c[static_cast<std::size_t>(species)].assign(values.begin(), values.end());
  transport().apply_dirichlet(c);
  concentrations_changed();
}

std::string BackendBase::save() const {
  require_initialized("save");
  BlobWriter w;
  write_blob_header(w, name(), state_version());
  save_state(w);
  return w.take();
}

void BackendBase::restore(std::string_view blob) {
  require_initialized("restore");
  BlobReader r(blob);
  const std::uint32_t version = read_blob_header(r, name());
  restore_state(r, version);
}

}  // namespace sadr::fluid
