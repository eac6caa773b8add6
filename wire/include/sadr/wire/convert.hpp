// SPDX-License-Identifier: MIT
/// \file convert.hpp
/// Conversions between wire messages (sadr.common.v1) and domain types.
/// Every from_proto() validates and throws sadr::InvalidArgument naming the
/// field, so generated types never reach a numerical core.
#pragma once

#include <array>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "sadr/common/inflow_box.hpp"
#include "sadr/common/particle_state.hpp"
#include "sadr/common/rate_law.hpp"
#include "sadr/common/status.hpp"
#include "sadr/common/v1/model.pb.h"
#include "sadr/common/v1/particles.pb.h"
#include "sadr/common/v1/status.pb.h"
#include "sadr/common/wall_surface.hpp"

namespace sadr::wire {

void to_proto(const Status& in, common::v1::Status& out);
Status from_proto(const common::v1::Status& in);

/// A rate law (common/rate_law.hpp) on the wire (rate_law_convert.cpp); from_proto
/// checks the type name (the law itself is checked when a core compiles it).
void to_proto(const rate_law::Definition& in, common::v1::RateLaw& out);
rate_law::Definition from_proto(const common::v1::RateLaw& in, std::string_view where);

void to_proto(const Box& in, common::v1::Box& out);
/// Throws InvalidArgument (prefixing `where`, e.g. "init.model.box") on bad input.
Box from_proto(const common::v1::Box& in, std::string_view where);

/// An inflow buffer (sadr.common.v1.InflowBuffer) as the cores' InflowBox; the
/// species is resolved by the service that applies it. Checks one bound per axis < dimension, lower
/// <= upper and a finite concentration >= 0; errors name `where` (e.g. "init.model.inflows[0]").
InflowBox from_proto(const common::v1::InflowBuffer& in, int dimension, std::string_view where);

/// A wall surface (sadr.common.v1.WallPlane, its region resolved by the caller): point and
/// normal 3 values each or empty (then 0 and +x), radius finite and >= 0; errors name `where`.
WallSurface from_proto(const common::v1::WallPlane& in, std::string_view where);

/// Per-particle wall surfaces (sadr.common.v1.WallTangents). from_proto checks them against the
/// particle count n (WallTangents::problems); errors name `where`.
void to_proto(const WallTangents& in, common::v1::WallTangents& out);
WallTangents from_proto(const common::v1::WallTangents& in, std::size_t n, std::string_view where);

/// Copies the arrays; velocities only if `with_velocities` and present.
void to_proto(const ParticleState& in, common::v1::ParticleState& out, bool with_velocities = true);
/// Checks lengths, finiteness, positivity (ParticleState::validate) and kind values.
ParticleState from_proto(const common::v1::ParticleState& in, std::string_view where);

/// The per-step geometry the SSA needs: dimension, positions, densities, masses and
/// kinds (they change along an open boundary; no velocities or ids: ids never change).
void geometry_to_proto(const ParticleState& in, common::v1::ParticleState& out);
/// Reads a state that may leave kinds and ids empty (geometry_to_proto's
/// output) into `out`, reusing its buffers: absent kinds and ids are taken
/// from `previous`, which must have the same particle count. A state with
/// ids is read as by from_proto. Validates like from_proto (finish_geometry).
void state_from_proto(const common::v1::ParticleState& in, const ParticleState& previous,
                      ParticleState& out, std::string_view where);
/// The tail of every geometry update: ids (and kinds, if `out` has none) from
/// `previous`; kinds given must be valid and keep every wall a wall and every other
/// particle a non-wall (fluid, inlet and outlet change into each other along an open
/// boundary); then validation, errors prefixed with `where`.
void finish_geometry(const ParticleState& previous, ParticleState& out, std::string_view where);

/// Region name -> particle indices.
using RegionMap = std::map<std::string, std::vector<std::uint32_t>, std::less<>>;
/// Checks names are unique and indices < n_particles; `where` prefixes errors.
RegionMap regions_from_proto(
    const google::protobuf::RepeatedPtrField<common::v1::RegionMembership>& regions,
    std::size_t n_particles, std::string_view where);
/// Particles of `name`; throws InvalidArgument listing the known regions if absent.
const std::vector<std::uint32_t>& region_particles(const RegionMap& regions, std::string_view name,
                                                   std::string_view where);
/// The sites of a boundary-flux reaction (`boundary_particles` with one `boundary_areas`
/// entry each, and no regions) into `particles` / `areas`; false if `rx` is no boundary flux.
/// Throws InvalidArgument at `where` if the two lists disagree or regions are also given.
bool boundary_flux_sites(const common::v1::Reaction& rx, std::string_view where,
                         std::vector<std::uint32_t>& particles, std::vector<double>& areas);

}  // namespace sadr::wire
