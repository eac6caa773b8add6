// SPDX-License-Identifier: MIT
// sadr.common.v1.RateLaw <-> rate_law::Definition.
#include <string>

#include "sadr/wire/convert.hpp"

namespace sadr::wire {

void to_proto(const rate_law::Definition& in, common::v1::RateLaw& out) {
  out.set_type(std::string(rate_law::to_string(in.type)));
  out.set_kcat(in.kcat);
  out.set_km(in.km);
  out.set_substrate(in.substrate);
  out.set_catalyst(in.catalyst);
  out.set_vmax(in.vmax);
  out.set_half(in.half);
  out.set_n(in.n);
  out.set_of(in.of);
  out.set_expression(in.expression);
  for (const auto& [name, value] : in.parameters) (*out.mutable_parameters())[name] = value;
  out.set_origin(in.origin);
}

rate_law::Definition from_proto(const common::v1::RateLaw& in, std::string_view where) {
  rate_law::Definition d;
  if (in.type() == "michaelis_menten") {
    d.type = rate_law::Type::kMichaelisMenten;
  } else if (in.type() == "hill") {
    d.type = rate_law::Type::kHill;
  } else if (in.type() == "expression") {
    d.type = rate_law::Type::kExpression;
  } else {
    throw InvalidArgument(std::string(where) + ".type = '" + in.type() +
                              "' (allowed: michaelis_menten, hill, expression)",
                          {{"field", std::string(where) + ".type"}, {"value", in.type()}});
  }
  d.kcat = in.kcat();
  d.km = in.km();
  d.substrate = in.substrate();
  d.catalyst = in.catalyst();
  d.vmax = in.vmax();
  d.half = in.half();
  d.n = in.n();
  d.of = in.of();
  d.expression = in.expression();
  for (const auto& [name, value] : in.parameters()) d.parameters[name] = value;
  d.origin = in.origin();
  return d;
}

}  // namespace sadr::wire
