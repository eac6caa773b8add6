// SPDX-License-Identifier: MIT
/// \file convert.hpp
/// Conversions between wire messages (sadr.common.v1) and domain types.
/// Every from_proto() validates and throws sadr::InvalidArgument naming the
/// field, so generated types never reach a numerical core.
#pragma once

#include <string_view>
#include <vector>

#include "sadr/common/particle_state.hpp"
#include "sadr/common/status.hpp"
#include "sadr/common/v1/particles.pb.h"
#include "sadr/common/v1/status.pb.h"

namespace sadr::wire {

void to_proto(const Status& in, common::v1::Status& out);
Status from_proto(const common::v1::Status& in);

void to_proto(const Box& in, common::v1::Box& out);
/// Throws InvalidArgument (prefixing `where`, e.g. "init.model.box") on bad input.
Box from_proto(const common::v1::Box& in, std::string_view where);

/// Copies the arrays; velocities only if `with_velocities` and present.
void to_proto(const ParticleState& in, common::v1::ParticleState& out, bool with_velocities = true);
/// Checks lengths, finiteness, positivity (ParticleState::validate) and kind values.
ParticleState from_proto(const common::v1::ParticleState& in, std::string_view where);

}  // namespace sadr::wire
