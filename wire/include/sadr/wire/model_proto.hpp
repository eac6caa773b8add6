// SPDX-License-Identifier: MIT
/// \file model_proto.hpp
/// The model's types (sadr/model/) on the wire: one to_proto and one from_proto per type.
/// from_proto() checks what the message's encoding allows to be wrong (enum values, vector
/// lengths, kinds) and throws InvalidArgument at `where`; the ranges are model::check()'s.
#pragma once

#include <string_view>

#include "sadr/common/v1/model.pb.h"
#include "sadr/fluid/v1/fluid_service.pb.h"
#include "sadr/model/chemistry.hpp"
#include "sadr/model/fluid.hpp"
#include "sadr/ssa/v1/ssa_service.pb.h"

namespace sadr::wire {

/// Inflow conditions are not walls: they travel as InflowBuffer (the sender resolves their
/// region to a box), so to_proto skips them and from_proto never makes one.
void to_proto(const model::Species& in, common::v1::Species& out);
model::Species from_proto(const common::v1::Species& in, std::string_view where);

/// `stochastic`, `reads_other` and `uses_time` are the sender's: the receiving service knows
/// which path it is and what its laws read.
void to_proto(const model::Reaction& in, common::v1::Reaction& out);
model::Reaction from_proto(const common::v1::Reaction& in, std::string_view where);

common::v1::WallCondition to_proto(model::BoundaryCondition condition);
model::BoundaryCondition from_proto(common::v1::WallCondition condition);

ssa::v1::JumpConvention to_proto(model::JumpConvention convention);
/// UNSPECIFIED keeps `fallback`.
model::JumpConvention from_proto(ssa::v1::JumpConvention convention,
                                 model::JumpConvention fallback);

void to_proto(const model::WallPlane& in, common::v1::WallPlane& out);

void to_proto(const model::OpenBoundarySettings& in, fluid::v1::OpenBoundary& out);
model::OpenBoundarySettings from_proto(const fluid::v1::OpenBoundary& in, std::string_view where);

}  // namespace sadr::wire
