// SPDX-License-Identifier: MIT
// A wall condition applies to the non-fluid particles of its region (docs/scene-format.md
// "boundaries"): a Dirichlet region that also holds fluid particles (fluid that moved into a
// geometric region, e.g. a scene started from a frame) holds its wall particles and leaves the
// fluid ones free; a region of fluid particles only is refused, naming the condition.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "sadr/common/status.hpp"
#include "sadr/ssa/ssa_service.hpp"
#include "sadr/wire/convert.hpp"
#include "service_probe.hpp"

namespace sadr::ssa {
namespace {

using testing::Probe;

// 1D line of 4 particles, unit volumes: wall, fluid, fluid, wall; species A held at 7
// molecules per unit length on region "left" = {0, 1} (one wall particle, one fluid particle).
v1::SsaRequest init_request(std::vector<std::uint32_t> left) {
  v1::SsaRequest r;
  auto* init = r.mutable_init();
  auto* m = init->mutable_model();
  testing::set_line_box(*m, 4.0, false);
  m->set_smoothing_length(1.5);
  auto* species = m->add_species();
  species->set_name("A");
  species->set_stochastic(true);
  species->set_diffusivity(0.1);
  auto* wall = species->add_walls();
  wall->set_region("left");
  wall->set_condition(common::v1::WALL_CONDITION_DIRICHLET);
  wall->set_value(7.0);
  auto* region = m->add_regions();
  region->set_name("left");
  for (const auto v : left) region->add_particles(v);
  ParticleState p;
  p.dimension = 1;
  p.resize(4, false);
  p.kinds = {ParticleKind::kWall, ParticleKind::kFluid, ParticleKind::kFluid, ParticleKind::kWall};
  for (std::size_t i = 0; i < 4; ++i) {
    p.positions[3 * i] = 0.5 + static_cast<double>(i);
    p.masses[i] = 1.0;
    p.densities[i] = 1.0;
  }
  wire::to_proto(p, *init->mutable_particles(), false);
  return r;
}

std::vector<std::int64_t> counts(Probe& h) {
  v1::SsaRequest r;
  r.mutable_get_counts();
  v1::SsaReply reply;
  h.call(r, reply);
  const auto& c = reply.get_counts().counts().species(0).counts();
  return {c.begin(), c.end()};
}

TEST(SsaWallRegion, ADirichletRegionWithFluidParticlesHoldsItsWallParticlesOnly) {
  Probe h;
  v1::SsaReply reply;
  h.call(init_request({0, 1}), reply);  // refused before: "1, which is not a wall particle"
  EXPECT_EQ(counts(h), (std::vector<std::int64_t>{7, 0, 0, 0}));
}

TEST(SsaWallRegion, ADirichletRegionOfFluidParticlesOnlyIsRefused) {
  Probe h;
  v1::SsaReply reply;
  try {
    h.call(init_request({1, 2}), reply);
    FAIL() << "accepted a Dirichlet region without wall particles";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("reservoirs[0]: its 2 particles are all fluid"),
              std::string::npos)
        << e.what();
  }
}

// SsaModel.wall_planes (sent by the orchestrator with fluid.wall_model morris) become the core's
// Morris walls: the region's particles and the surface; an unknown region is refused.
TEST(SsaWallRegion, WallPlanesBecomeMorrisWalls) {
  v1::SsaRequest r = init_request({0});
  auto* plane = r.mutable_init()->mutable_model()->add_wall_planes();
  plane->set_region("left");
  for (double x : {0.75, 0.0, 0.0}) plane->add_point(x);
  for (double n : {1.0, 0.0, 0.0}) plane->add_normal(n);
  std::vector<std::string> names;
  const Model m = model_from_proto(r.init().model(), 4, names);
  ASSERT_EQ(m.morris_walls.size(), 1U);
  EXPECT_EQ(m.morris_walls[0].voxels, (std::vector<std::uint32_t>{0}));
  EXPECT_EQ(m.morris_walls[0].surface.point[0], 0.75);
  EXPECT_EQ(m.morris_walls[0].surface.inward_normal[0], 1.0);
  EXPECT_EQ(m.morris_walls[0].surface.radius, 0.0);
  plane->set_region("nowhere");
  try {
    (void)model_from_proto(r.init().model(), 4, names);
    FAIL() << "accepted a wall plane on an unknown region";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("init.model.wall_planes[0]"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace sadr::ssa
