// SPDX-License-Identifier: MIT
// Free walls (Model::free_walls): validation, per-voxel roles and weight sums, snapshot.
#include <gtest/gtest.h>

#include <functional>
#include <span>
#include <string>
#include <vector>

#include "sadr/common/status.hpp"
#include "sadr/ssa/direct_solver.hpp"
#include "sadr/ssa/nsm_solver.hpp"
#include "ssa_test_support.hpp"

namespace sadr::ssa {
namespace {

using testing::message_of;

// 1D chain of 6 (dx = 1, h = 1.5: nearest neighbours only), walls at 0 and 5.
ParticleState chain6() {
  ParticleState p = testing::make_lattice(1, 6, 1.0);
  p.kinds[0] = p.kinds[5] = ParticleKind::kWall;
  return p;
}

Model chain_model() {
  Model m = testing::diffusion_model(testing::make_box(1, 6.0, false), 1.5, 1.0);
  m.species.push_back({"B", 1.0});
  return m;
}

TEST(FreeWalls, ReservoirAndFreeConflictIsRejectedNamingSpeciesAndVoxel) {
  Model m = chain_model();
  m.reservoirs = {{1, 3.0, {0, 5}}};
  m.free_walls = {{1, {5}}};
  const std::string msg = message_of([&] { m.validate(); });
  EXPECT_NE(msg.find("free_walls[0]"), std::string::npos) << msg;
  EXPECT_NE(msg.find("species 1"), std::string::npos) << msg;
  EXPECT_NE(msg.find("voxel 5"), std::string::npos) << msg;
  EXPECT_THROW(NsmSolver(m, 1), InvalidArgument);

  m.reservoirs = {{1, 3.0, {}}};
  m.free_walls = {{1, {}}};  // every wall both
  EXPECT_NE(message_of([&] { m.validate(); }).find("both free and a reservoir"), std::string::npos);

  m.free_walls = {{2, {0}}};
  EXPECT_NE(message_of([&] { m.validate(); }).find("free_walls[0].species = 2"), std::string::npos);
}

TEST(FreeWalls, IndicesAreCheckedAgainstTheParticles) {
  Model m = chain_model();
  m.free_walls = {{0, {6}}};
  NsmSolver s(m, 1);
  const std::string msg = message_of([&] { s.update_graph(chain6()); });
  EXPECT_NE(msg.find("free_walls[0].voxels contains 6"), std::string::npos) << msg;
  EXPECT_FALSE(s.state().has_graph());  // checked before anything was built
  m.free_walls = {{0, {2}}};            // a fluid particle
  NsmSolver t(m, 1);
  EXPECT_NE(message_of([&] { t.update_graph(chain6()); }).find("not a wall particle"),
            std::string::npos);
}

TEST(FreeWalls, RolesAndWeightSumsPerSpecies) {
  Model m = chain_model();
  m.free_walls = {{0, {0}}};        // A: wall 0 free, wall 5 no-flux
  m.reservoirs = {{1, 2.0, {}}};    // B: walls are reservoirs ...
  m.free_walls.push_back({1, {}});  // ... except that all walls are free for B
  m.reservoirs[0].voxels = {5};     // explicit reservoir beats all-walls free
  NsmSolver s(m, 1);
  s.update_graph(chain6());
  const RdmeState& st = s.state();
  using R = RdmeState::VoxelRole;
  EXPECT_EQ(st.role(0, 0), R::kOpen);
  EXPECT_EQ(st.role(0, 5), R::kClosed);
  EXPECT_EQ(st.role(0, 2), R::kOpen);
  EXPECT_EQ(st.role(1, 0), R::kOpen);
  EXPECT_EQ(st.role(1, 5), R::kReservoir);
  const double w = s.graph().edges[s.graph().row_start[2]].weight;  // uniform chain weight
  EXPECT_DOUBLE_EQ(st.jump_weight_sum(0, 0), w);                    // wall 0 -> 1
  EXPECT_DOUBLE_EQ(st.jump_weight_sum(0, 1), 2 * w);                // 1 -> 0 (free) and 1 -> 2
  EXPECT_DOUBLE_EQ(st.jump_weight_sum(0, 4), w);                    // 4 -> 5 is no-flux
  EXPECT_DOUBLE_EQ(st.jump_weight_sum(0, 5), 0.0);
  EXPECT_DOUBLE_EQ(st.jump_weight_sum(1, 4), 2 * w);  // into the reservoir: absorbed
  EXPECT_DOUBLE_EQ(st.jump_weight_sum(1, 5), w);
  EXPECT_EQ(s.counts(1)[5], 2);  // reservoir count round(C V)
  EXPECT_EQ(s.counts(1)[0], 0);  // free wall: no reservoir
  EXPECT_TRUE(st.fixed(1, 5));
  EXPECT_FALSE(st.fixed(1, 0));
  EXPECT_NE(m.fingerprint(), chain_model().fingerprint());
}

TEST(FreeWalls, MoleculesEnterAndLeaveAFreeWallAndNeverTheClosedOne) {
  Model m = chain_model();
  m.free_walls = {{0, {0}}};
  for (int solver = 0; solver < 2; ++solver) {
    std::int64_t in_free_wall = 0;
    std::vector<std::int64_t> x{0, 5, 5, 5, 5, 0};
    auto check = [&](std::span<const std::int64_t> c) {
      std::int64_t total = 0;
      for (auto v : c) total += v;
      EXPECT_EQ(total, 20);
      EXPECT_EQ(c[5], 0);
      in_free_wall += c[0];
    };
    if (solver == 0) {
      NsmSolver s(m, 7);
      s.update_graph(chain6());
      s.set_counts(0, x);
      for (int k = 1; k <= 50; ++k) s.advance(0.2 * k), check(s.counts(0));
    } else {
      DirectSolver s(m, 7);
      s.update_graph(chain6());
      s.set_counts(0, x);
      for (int k = 1; k <= 50; ++k) s.advance(0.2 * k), check(s.counts(0));
    }
    EXPECT_GT(in_free_wall, 0) << "solver " << solver;
  }
}

TEST(FreeWalls, SnapshotRestoresBitIdentically) {
  Model m = chain_model();
  m.free_walls = {{0, {0}}, {1, {}}};
  m.reservoirs = {{1, 2.0, {5}}};
  m.reactions = {{"wall", {{0, 1}}, {{1, 1}}, 0.5, {ParticleKind::kWall}, {}}};
  NsmSolver a(m, 3);
  a.update_graph(chain6());
  a.set_counts(0, std::vector<std::int64_t>{0, 9, 9, 9, 9, 0});
  a.advance(1.3);
  const std::string blob = a.save();
  a.advance(4.0);
  NsmSolver b(m, 4);
  b.restore(blob);
  b.advance(4.0);
  EXPECT_EQ(a.save(), b.save());
}

}  // namespace
}  // namespace sadr::ssa
