// SPDX-License-Identifier: MIT
// The model's types on the wire: to_proto then from_proto gives back what the receiving service
// may know (wire/model_proto.hpp), and the encoding's own errors are refused at their field.
#include <gtest/gtest.h>

#include <string>

#include "sadr/common/status.hpp"
#include "sadr/wire/model_proto.hpp"

namespace sadr::wire {
namespace {

TEST(ModelProto, SpeciesRoundTripsWithoutInflow) {
  model::Species s;
  s.name = "L";
  s.stochastic = false;
  s.diffusivity = 0.25;
  s.boundaries = {{"membrane", model::BoundaryCondition::kFree, 0.0},
                  {"inlet", model::BoundaryCondition::kInflow, 3.0},  // travels as InflowBuffer
                  {"", model::BoundaryCondition::kDirichlet, 1.5},
                  {"top", model::BoundaryCondition::kNeumann, -0.5}};
  common::v1::Species msg;
  to_proto(s, msg);
  const model::Species back = from_proto(msg, "species[0]");
  EXPECT_EQ(back.name, "L");
  EXPECT_FALSE(back.stochastic);
  EXPECT_EQ(back.diffusivity, 0.25);
  ASSERT_EQ(back.boundaries.size(), 3u);
  EXPECT_EQ(back.boundaries[0].condition, model::BoundaryCondition::kFree);
  EXPECT_EQ(back.boundaries[1].region, "");
  EXPECT_EQ(back.boundaries[1].value, 1.5);
  EXPECT_EQ(back.boundaries[2].condition, model::BoundaryCondition::kNeumann);
  EXPECT_EQ(back.boundaries[2].value, -0.5);
}

TEST(ModelProto, ReactionRoundTrips) {
  model::Reaction r;
  r.name = "bind";
  r.reactants = {{"L", 1}, {"R", 1}};
  r.products = {{"C", 1}};
  r.rate = 2.5;
  r.kinds = {ParticleKind::kFluid, ParticleKind::kWall};
  r.regions = {"membrane"};
  common::v1::Reaction msg;
  to_proto(r, msg);
  const model::Reaction back = from_proto(msg, "reactions[0]");
  EXPECT_EQ(back.name, r.name);
  EXPECT_EQ(back.reactants, r.reactants);
  EXPECT_EQ(back.products, r.products);
  EXPECT_EQ(back.rate, r.rate);
  EXPECT_EQ(back.kinds, r.kinds);
  EXPECT_EQ(back.regions, r.regions);
  EXPECT_FALSE(back.law.has_value());

  model::Reaction flux;
  flux.name = "release";
  flux.products = {{"L", 1}};
  flux.law = rate_law::Definition{};
  flux.law->type = rate_law::Type::kExpression;
  flux.law->expression = "2";
  flux.boundary_particles = {7, 9};
  flux.boundary_areas = {0.1, 0.2};
  common::v1::Reaction fmsg;
  to_proto(flux, fmsg);
  const model::Reaction fback = from_proto(fmsg, "reactions[1]");
  EXPECT_EQ(fback.boundary_particles, flux.boundary_particles);
  EXPECT_EQ(fback.boundary_areas, flux.boundary_areas);
  ASSERT_TRUE(fback.law.has_value());
  EXPECT_EQ(fback.law->expression, "2");
}

TEST(ModelProto, EncodingErrorsNameTheirField) {
  common::v1::Reaction msg;
  msg.add_kinds(9);
  try {
    (void)from_proto(msg, "init.model.reactions[2]");
    FAIL() << "kind 9 must be refused";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("init.model.reactions[2].kinds[0] = 9 (allowed: 0..3)"),
              std::string::npos)
        << e.what();
  }
  fluid::v1::OpenBoundary ob;
  ob.set_axis(3);
  EXPECT_THROW((void)from_proto(ob, "open_boundary"), InvalidArgument);
}

TEST(ModelProto, ConventionAndOpenBoundaryRoundTrip) {
  for (auto c : {model::JumpConvention::kSymmetric, model::JumpConvention::kVolume}) {
    EXPECT_EQ(from_proto(to_proto(c), model::JumpConvention::kSymmetric), c);
  }
  EXPECT_EQ(from_proto(ssa::v1::JUMP_CONVENTION_UNSPECIFIED, model::JumpConvention::kVolume),
            model::JumpConvention::kVolume);
  model::OpenBoundarySettings in;
  in.axis = 0;
  in.inlet_lo = -0.2;
  in.fluid_lo = 0.0;
  in.fluid_hi = 1.0;
  in.outlet_hi = 1.2;
  in.parabolic = true;
  in.mean_velocity = 0.3;
  in.cross_axis = 1;
  in.wall_lo = 0.0;
  in.wall_hi = 0.5;
  fluid::v1::OpenBoundary msg;
  to_proto(in, msg);
  const model::OpenBoundarySettings back = from_proto(msg, "open_boundary");
  EXPECT_EQ(back.inlet_lo, in.inlet_lo);
  EXPECT_EQ(back.outlet_hi, in.outlet_hi);
  EXPECT_TRUE(back.parabolic);
  EXPECT_EQ(back.mean_velocity, in.mean_velocity);
  EXPECT_EQ(back.wall_hi, in.wall_hi);
}

}  // namespace
}  // namespace sadr::wire
