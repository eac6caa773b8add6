// SPDX-License-Identifier: MIT
#include "sadr/wire/convert.hpp"

#include <cmath>
#include <limits>
#include <string>

namespace sadr::wire {

void to_proto(const Status& in, common::v1::Status& out) {
  out.set_code(static_cast<common::v1::StatusCode>(static_cast<int>(in.code)));
  out.set_message(in.message);
  out.clear_details();
  for (const auto& [k, v] : in.details) {
    auto* d = out.add_details();
    d->set_key(k);
    d->set_value(v);
  }
}

Status from_proto(const common::v1::Status& in) {
  Status s;
  const int code = static_cast<int>(in.code());
  s.code = (code >= 0 && code <= static_cast<int>(StatusCode::kAborted))
               ? static_cast<StatusCode>(code)
               : StatusCode::kInternal;
  s.message = in.message();
  for (const auto& d : in.details()) s.details.emplace_back(d.key(), d.value());
  return s;
}

void to_proto(const Box& in, common::v1::Box& out) {
  out.set_dimension(static_cast<std::uint32_t>(in.dimension));
  out.clear_lower();
  out.clear_upper();
  out.clear_periodic();
  for (int a = 0; a < 3; ++a) {
    out.add_lower(in.lo[a]);
    out.add_upper(in.hi[a]);
    out.add_periodic(in.periodic[a]);
  }
}

Box from_proto(const common::v1::Box& in, std::string_view where) {
  auto bad = [&](const std::string& what) {
    return InvalidArgument(std::string(where) + ": " + what);
  };
  if (in.lower_size() != 3 || in.upper_size() != 3 || in.periodic_size() != 3) {
    throw bad("lower, upper and periodic need 3 values each (got " +
              std::to_string(in.lower_size()) + ", " + std::to_string(in.upper_size()) + ", " +
              std::to_string(in.periodic_size()) + ")");
  }
  Box b;
  b.dimension = static_cast<int>(in.dimension());
  for (int a = 0; a < 3; ++a) {
    b.lo[a] = in.lower(a);
    b.hi[a] = in.upper(a);
    b.periodic[a] = in.periodic(a);
  }
  try {
    b.validate();
  } catch (const InvalidArgument& e) {
    throw bad(e.what());
  }
  return b;
}

InflowBox from_proto(const common::v1::InflowBuffer& in, int dimension, std::string_view where) {
  const std::string at(where);
  if (in.lower_size() != dimension || in.upper_size() != dimension) {
    throw InvalidArgument(at + ": lower/upper have " + std::to_string(in.lower_size()) + "/" +
                              std::to_string(in.upper_size()) +
                              " entries (allowed: " + std::to_string(dimension) + ", one per axis)",
                          {{"field", at + ".lower"}});
  }
  constexpr double kInf = std::numeric_limits<double>::infinity();
  InflowBox b;
  b.species = in.species();
  b.lower = {-kInf, -kInf, -kInf};
  b.upper = {kInf, kInf, kInf};
  for (int a = 0; a < dimension; ++a) {
    b.lower[a] = in.lower(a);
    b.upper[a] = in.upper(a);
    if (std::isnan(b.lower[a]) || std::isnan(b.upper[a]) || !(b.lower[a] <= b.upper[a])) {
      throw InvalidArgument(
          at + ": axis " + std::to_string(a) + " has lower = " + format_value(b.lower[a]) +
              " > upper = " + format_value(b.upper[a]) + " (allowed: lower <= upper)",
          {{"field", at + ".lower"}});
    }
  }
  b.concentration = in.concentration();
  if (!std::isfinite(b.concentration) || b.concentration < 0) {
    throw InvalidArgument(
        at + ".concentration = " + format_value(b.concentration) +
            " (allowed: finite, >= 0 molecules/length^d)",
        {{"field", at + ".concentration"}, {"value", format_value(b.concentration)}});
  }
  return b;
}

void to_proto(const ParticleState& in, common::v1::ParticleState& out, bool with_velocities) {
  out.set_dimension(static_cast<std::uint32_t>(in.dimension));
  out.mutable_positions()->Assign(in.positions.begin(), in.positions.end());
  out.mutable_densities()->Assign(in.densities.begin(), in.densities.end());
  out.mutable_masses()->Assign(in.masses.begin(), in.masses.end());
  if (with_velocities) {
    out.mutable_velocities()->Assign(in.velocities.begin(), in.velocities.end());
  } else {
    out.clear_velocities();
  }
  auto* kinds = out.mutable_kinds();
  kinds->Clear();
  kinds->Reserve(static_cast<int>(in.kinds.size()));
  for (auto k : in.kinds) kinds->Add(static_cast<std::uint32_t>(k));
  out.mutable_ids()->Assign(in.ids.begin(), in.ids.end());
}

WallSurface from_proto(const common::v1::WallPlane& in, std::string_view where) {
  const std::string at(where);
  auto vec3 = [&](const google::protobuf::RepeatedField<double>& v, const std::string& field,
                  std::array<double, 3> fallback) {
    if (v.empty()) return fallback;
    if (v.size() != 3) {
      throw InvalidArgument(at + field + " needs 3 values, got " + std::to_string(v.size()));
    }
    return std::array<double, 3>{v[0], v[1], v[2]};
  };
  WallSurface s;
  s.point = vec3(in.point(), ".point", {0, 0, 0});
  s.inward_normal = vec3(in.normal(), ".normal", {1, 0, 0});
  if (!(in.radius() >= 0) || !std::isfinite(in.radius())) {
    throw InvalidArgument(at + ".radius = " + std::to_string(in.radius()) +
                          " (allowed: 0 for a plane, or a finite length > 0 for a circle / "
                          "sphere)");
  }
  s.radius = in.radius();
  return s;
}

void to_proto(const WallTangents& in, common::v1::WallTangents& out) {
  out.mutable_particles()->Assign(in.particles.begin(), in.particles.end());
  out.mutable_depths()->Assign(in.depths.begin(), in.depths.end());
  out.mutable_normals()->Assign(in.normals.begin(), in.normals.end());
}

WallTangents from_proto(const common::v1::WallTangents& in, std::size_t n, std::string_view where) {
  WallTangents t;
  t.particles.assign(in.particles().begin(), in.particles().end());
  t.depths.assign(in.depths().begin(), in.depths().end());
  t.normals.assign(in.normals().begin(), in.normals().end());
  const auto problems = t.problems(n);
  if (!problems.empty()) {
    std::string msg(where);
    msg.append(": ");
    for (std::size_t k = 0; k < problems.size(); ++k) {
      if (k > 0) msg.append("; ");
      msg.append(problems[k]);
    }
    throw InvalidArgument(msg);
  }
  return t;
}

namespace {

/// in.kinds into `kinds` (resized), each checked to be a ParticleKind value.
void kinds_from_proto(const common::v1::ParticleState& in, std::vector<ParticleKind>& kinds,
                      std::string_view where) {
  kinds.resize(static_cast<std::size_t>(in.kinds_size()));
  for (int i = 0; i < in.kinds_size(); ++i) {
    const std::uint32_t k = in.kinds(i);
    if (k > static_cast<std::uint32_t>(ParticleKind::kOutlet)) {
      throw InvalidArgument(std::string(where) + ": kinds[" + std::to_string(i) + "] = " +
                            std::to_string(k) + " (allowed: 0 fluid, 1 wall, 2 inlet, 3 outlet)");
    }
    kinds[static_cast<std::size_t>(i)] = static_cast<ParticleKind>(k);
  }
}

}  // namespace

ParticleState from_proto(const common::v1::ParticleState& in, std::string_view where) {
  ParticleState s;
  s.dimension = static_cast<int>(in.dimension());
  s.positions.assign(in.positions().begin(), in.positions().end());
  s.densities.assign(in.densities().begin(), in.densities().end());
  s.masses.assign(in.masses().begin(), in.masses().end());
  s.velocities.assign(in.velocities().begin(), in.velocities().end());
  s.ids.assign(in.ids().begin(), in.ids().end());
  kinds_from_proto(in, s.kinds, where);
  try {
    s.validate();
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(std::string(where) + ": " + e.what());
  }
  return s;
}

void geometry_to_proto(const ParticleState& in, common::v1::ParticleState& out) {
  out.set_dimension(static_cast<std::uint32_t>(in.dimension));
  out.mutable_positions()->Assign(in.positions.begin(), in.positions.end());
  out.mutable_densities()->Assign(in.densities.begin(), in.densities.end());
  out.mutable_masses()->Assign(in.masses.begin(), in.masses.end());
  out.clear_velocities();
  auto* kinds = out.mutable_kinds();
  kinds->Clear();
  kinds->Reserve(static_cast<int>(in.kinds.size()));
  for (auto k : in.kinds) kinds->Add(static_cast<std::uint32_t>(k));
  out.clear_ids();
}

void state_from_proto(const common::v1::ParticleState& in, const ParticleState& previous,
                      ParticleState& out, std::string_view where) {
  if (in.ids_size() > 0) {
    out = from_proto(in, where);
    return;
  }
  const std::size_t n = static_cast<std::size_t>(in.densities_size());
  if (n != previous.size()) {
    throw InvalidArgument(
        std::string(where) + ": " + std::to_string(n) + " densities, expected one per particle (" +
        std::to_string(previous.size()) + "; the particle set cannot change after Init)");
  }
  out.dimension = static_cast<int>(in.dimension());
  out.positions.assign(in.positions().begin(), in.positions().end());
  out.densities.assign(in.densities().begin(), in.densities().end());
  out.masses.assign(in.masses().begin(), in.masses().end());
  out.velocities.assign(in.velocities().begin(), in.velocities().end());
  kinds_from_proto(in, out.kinds, where);
  finish_geometry(previous, out, where);
}

void finish_geometry(const ParticleState& previous, ParticleState& out, std::string_view where) {
  if (out.kinds.empty()) {
    out.kinds = previous.kinds;
  } else if (out.kinds.size() == previous.kinds.size()) {
    // Kinds may change along an open boundary (fluid <-> inlet <-> outlet); walls never do.
    for (std::size_t i = 0; i < out.kinds.size(); ++i) {
      const ParticleKind k = out.kinds[i], was = previous.kinds[i];
      if (k > ParticleKind::kOutlet) {
        throw InvalidArgument(std::string(where) + ": kinds[" + std::to_string(i) +
                              "] = " + std::to_string(static_cast<int>(k)) +
                              " (allowed: 0 fluid, 1 wall, 2 inlet, 3 outlet)");
      }
      if ((k == ParticleKind::kWall) != (was == ParticleKind::kWall)) {
        throw InvalidArgument(std::string(where) + ": particle " + std::to_string(i) +
                              " changed kind from " + std::string(to_string(was)) + " to " +
                              std::string(to_string(k)) +
                              " (allowed: fluid, inlet and outlet change into each other; wall "
                              "particles stay walls)");
      }
    }
  }
  out.ids = previous.ids;
  try {
    out.validate();
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(std::string(where) + ": " + e.what());
  }
}

RegionMap regions_from_proto(
    const google::protobuf::RepeatedPtrField<common::v1::RegionMembership>& regions,
    std::size_t n_particles, std::string_view where) {
  RegionMap out;
  for (int r = 0; r < regions.size(); ++r) {
    const auto& reg = regions.Get(r);
    const std::string here = std::string(where) + ".regions[" + std::to_string(r) + "]";
    if (reg.name().empty()) throw InvalidArgument(here + ".name is empty");
    if (out.count(reg.name())) {
      throw InvalidArgument(here + ".name = '" + reg.name() + "' is used twice");
    }
    std::vector<std::uint32_t> idx(reg.particles().begin(), reg.particles().end());
    for (std::size_t k = 0; k < idx.size(); ++k) {
      if (idx[k] >= n_particles) {
        throw InvalidArgument(here + ".particles[" + std::to_string(k) +
                              "] = " + std::to_string(idx[k]) + " (allowed: 0.." +
                              std::to_string(n_particles - 1) + ")");
      }
    }
    out.emplace(reg.name(), std::move(idx));
  }
  return out;
}

const std::vector<std::uint32_t>& region_particles(const RegionMap& regions, std::string_view name,
                                                   std::string_view where) {
  const auto it = regions.find(name);
  if (it != regions.end()) return it->second;
  std::string known;
  for (const auto& [k, v] : regions) known += (known.empty() ? "" : ", ") + k;
  throw InvalidArgument(std::string(where) + ": unknown region '" + std::string(name) +
                        "' (known: " + (known.empty() ? "none" : known) + ")");
}

bool boundary_flux_sites(const common::v1::Reaction& rx, std::string_view where,
                         std::vector<std::uint32_t>& particles, std::vector<double>& areas) {
  if (rx.boundary_particles_size() == 0 && rx.boundary_areas_size() == 0) return false;
  if (rx.regions_size() > 0 || rx.boundary_particles_size() != rx.boundary_areas_size()) {
    throw InvalidArgument(std::string(where) +
                          ": a boundary flux has no regions and one area per particle (" +
                          std::to_string(rx.boundary_particles_size()) + " particles, " +
                          std::to_string(rx.boundary_areas_size()) + " areas)");
  }
  particles.assign(rx.boundary_particles().begin(), rx.boundary_particles().end());
  areas.assign(rx.boundary_areas().begin(), rx.boundary_areas().end());
  return true;
}

}  // namespace sadr::wire
