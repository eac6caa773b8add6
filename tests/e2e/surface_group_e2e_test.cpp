// SPDX-License-Identifier: MIT
// A boundary flux through one physical group of a mesh body's surface (scene `boundary_fluxes`
// with `surface` and `group`), end to end on the static backend: a 2D channel read from a gmsh
// .msh file, (0,0) (2,0) (2,1) (0,1.2), whose curves "inlet" (x = 0, length 1.2) and "outlet"
// (x = 2, length 1) are groups. Released from t = 0 at a constant flux density j:
//  - C (deterministic, diffusing, decaying at rate k) through the inlet: the amount obeys
//    dN/dt = j A - k N whatever the diffusion, N(t) = j A (1 - e^{-kt}) / k with A = 1.2;
//  - S (deterministic, not diffusing) through the outlet: N(t) = j A t with A = 1, and S is
//    nonzero only on the fluid column next to the outlet (x = 1.95 at spacing 0.1);
//  - X (stochastic, not diffusing) through the inlet: the total is Poisson(j A t) (births only,
//    from zero), and every molecule sits on the column next to the inlet (x = 0.05).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "cli_test_support.hpp"

namespace sadr::e2e {
namespace {

constexpr double kGroupT = 4.0;

const char* const kGroupMsh =
    "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
    "$PhysicalNames\n4\n1 1 \"inlet\"\n1 2 \"outlet\"\n1 3 \"walls\"\n2 4 \"channel\"\n"
    "$EndPhysicalNames\n"
    "$Nodes\n5\n1 0 0 0\n2 2 0 0\n3 2 1 0\n4 0 1.2 0\n5 0 0.5 0\n$EndNodes\n"
    "$Elements\n8\n"
    "1 1 2 1 1 1 5\n2 1 2 1 1 5 4\n3 1 2 2 2 2 3\n4 1 2 3 3 1 2\n5 1 2 3 3 3 4\n"
    "6 2 2 4 4 1 2 5\n7 2 2 4 4 5 2 3\n8 2 2 4 4 5 3 4\n"
    "$EndElements\n";

const char* const kGroupScene = R"yaml(name: surface_group_channel
dimension: 2
box: {lower: [-0.5, -0.5], upper: [2.5, 1.7]}
geometry:
  spacing: 0.1
  bodies:
    - {name: duct, role: fluid, shape: {type: mesh, file: channel.msh}}
fluid: {backend: static, h_over_dx: 2.0, parameters: {diffusion_eps: 0}}
species:
  - {name: C, stochastic: false, diffusivity: 0.25}
  - {name: S, stochastic: false, diffusivity: 0}
  - {name: X, diffusivity: 0}
reactions:
  - {name: decay_c, equation: "C -> 0", rate: 1.0}
boundary_fluxes:
  - {name: feed_c, species: C, surface: duct, group: inlet,
     law: {type: expression, expression: "1"}}
  - {name: feed_s, species: S, surface: duct, group: outlet,
     law: {type: expression, expression: "2"}}
  - {name: feed_x, species: X, surface: duct, group: inlet,
     law: {type: expression, expression: "50"}}
time: {coupling_step: 0.5, end: 4.0}
output: {times: [4.0], formats: [csv]}
seed: 5
)yaml";

TEST(SurfaceGroupE2e, EachGroupReleasesJTimesItsOwnLengthNextToItselfOnly) {
  const fs::path d = scratch("surface-group");
  const fs::path s = write_scene(d, kGroupScene);
  std::ofstream(d / "channel.msh") << kGroupMsh;
  const std::string cmd =
      bin("sadr") + " run " + s.string() + " -q --embedded -o " + (d / "out").string();
  ASSERT_EQ(run(cmd, d / "run.log"), 0) << read_file(d / "run.log");
  const auto files = frames(d / "out");
  ASSERT_EQ(files.size(), 2u);  // t = 0 and t = 4
  const CsvFrame f = read_csv(files.back());
  ASSERT_NEAR(f.column("time")[0], kGroupT, 1e-12);
  const auto& x = f.column("x");
  const auto& kind = f.column("kind");
  const auto& m = f.column("mass");
  const auto& rho = f.column("density");
  const auto& c = f.column("C");
  const auto& sv = f.column("S");
  const auto& xs = f.column("X");
  double amount_c = 0, amount_s = 0, total_x = 0;
  std::size_t outlet_column = 0;
  for (std::size_t i = 0; i < f.rows(); ++i) {
    const double v = m[i] / rho[i];
    amount_c += c[i] * v;
    amount_s += sv[i] * v;
    total_x += xs[i];
    if (kind[i] != 0) {
      EXPECT_EQ(sv[i], 0.0) << "wall particle " << i;
      EXPECT_EQ(xs[i], 0.0) << "wall particle " << i;
      continue;
    }
    const bool at_outlet = std::fabs(x[i] - 1.95) < 1e-9;
    const bool at_inlet = std::fabs(x[i] - 0.05) < 1e-9;
    if (!at_outlet) {
      EXPECT_EQ(sv[i], 0.0) << "particle " << i << " at x = " << x[i];
    }
    if (!at_inlet) {
      EXPECT_EQ(xs[i], 0.0) << "particle " << i << " at x = " << x[i];
    }
    if (at_outlet && sv[i] > 0) ++outlet_column;
  }
  // The outlet's column: the 10 fluid sites y = 0.05 ... 0.95.
  EXPECT_EQ(outlet_column, 10u);
  const double n_c = 1.0 * 1.2 * (1 - std::exp(-kGroupT));
  const double n_s = 2.0 * 1.0 * kGroupT;
  const double n_x = 50.0 * 1.2 * kGroupT;
  const double z = (total_x - n_x) / std::sqrt(n_x);
  std::printf(
      "inlet C: %.9g against %.9g; outlet S: %.12g against %.12g; inlet X: %.0f against "
      "%.1f (z = %.2f)\n",
      amount_c, n_c, amount_s, n_s, total_x, n_x, z);
  EXPECT_NEAR(amount_c / n_c, 1.0, 1e-6);
  EXPECT_NEAR(amount_s / n_s, 1.0, 1e-9);
  EXPECT_LE(std::fabs(z), 3.29);  // a false failure once in 1000 runs
  if (!HasFailure()) fs::remove_all(d);
}

}  // namespace
}  // namespace sadr::e2e
