// SPDX-License-Identifier: MIT
// A moving body end to end through `sadr run` (docs/scene-format.md "Moving bodies"): an
// elliptic cell made by `geometry` travels along a periodic channel at 0.5 and turns at 1 rad
// per unit time (`motion: {..., moves: true}`), receptors R on its membrane bind a ligand L of
// the flow (stochastic species, `free` boundaries on the membrane, a reaction there). Checked on
// the CSV frames: the cell's wall particles sit at the closed-form rigid motion and carry its
// velocity; R and RL stay on the cell's wall particles wherever they are and R + RL is
// conserved; binding happens on the moving membrane; a run stopped at t = 0.5 and resumed writes
// the same frames; `sadr summary` finds no fluid inside walls (its tangent-plane test with the
// cell's planes turned to each frame's time).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <string>

#include "cli_test_support.hpp"

namespace sadr::e2e {
namespace {

const char* const kScene = R"(name: moving_cell
dimension: 2
box: {lower: [0.0, -0.15], upper: [2.0, 1.15], periodic: [true, false]}
geometry:
  spacing: 0.05
  bodies:
    - {name: channel, role: fluid, shape: {type: box, lower: [-1.0, 0.0], upper: [3.0, 1.0]}}
    - name: cell
      role: solid
      shape: {type: ellipse, center: [0.7, 0.5], radii: [0.2, 0.15]}
      wall_layer: membrane
      motion: {velocity: [0.5, 0.0], angular_velocity: 1.0, center: [0.7, 0.5], moves: true}
fluid:
  backend: sdpd
  h_over_dx: 3.0
  sound_speed: 40.0   # 57 x the fastest wall: at 10 (and 20) up to 2 (1) fluid particles get
                      # 0.5 (0.2) spacings inside the turning, travelling ellipse
  shear_viscosity: 0.1
  wall_model: adami
species:
  - name: L
    diffusivity: 0.01
    initial: [{region: channel, count: 5}]
    boundaries: [{region: membrane, condition: free}]
  - name: R
    diffusivity: 0.0
    initial: [{region: membrane, count: 20}]
    boundaries: [{region: membrane, condition: free}]
  - name: RL
    diffusivity: 0.0
    boundaries: [{region: membrane, condition: free}]
reactions:
  - {name: binding, equation: "R + L <-> RL", rate: 0.5, reverse_rate: 0.1, kinds: [wall],
     regions: [membrane]}
time: {coupling_step: 0.02, end: 1.0}
output: {every: 0.25, formats: [csv]}
seed: 5
)";

constexpr double kV = 0.5, kW = 1.0, kCx = 0.7, kCy = 0.5, kEvery = 0.25;

TEST(MovingBodyE2e, CellTravelsAndTurnsWithItsReceptors) {
  const fs::path d = scratch("moving-body");
  const fs::path scene = write_scene(d, kScene);
  ASSERT_EQ(
      run(bin("sadr") + " run " + scene.string() + " -q --embedded -o " + (d / "out").string(),
          d / "run.log"),
      0)
      << read_file(d / "run.log");
  const auto fr = frames(d / "out");
  ASSERT_EQ(fr.size(), 5U);
  const CsvFrame first = read_csv(fr.front());
  // the cell's wall particles: wall particles inside the channel (its walls lie beyond y 0, 1)
  std::map<long, std::array<double, 2>> x0;
  for (std::size_t i = 0; i < first.rows(); ++i) {
    const double y = first.column("y")[i];
    if (first.column("kind")[i] != 0 && y > 0.0 && y < 1.0) {
      x0[std::lround(first.column("id")[i])] = {first.column("x")[i], y};
    }
  }
  ASSERT_GT(x0.size(), 30U);  // 36 lattice sites inside the ellipse
  double worst_x = 0, worst_v = 0, total0 = -1;
  for (std::size_t k = 0; k < fr.size(); ++k) {
    const CsvFrame f = read_csv(fr[k]);
    const double t = kEvery * static_cast<double>(k), c = std::cos(kW * t), s = std::sin(kW * t);
    double bound = 0, total = 0;
    for (std::size_t i = 0; i < f.rows(); ++i) {
      const auto it = x0.find(std::lround(f.column("id")[i]));
      const double r = f.column("R")[i], rl = f.column("RL")[i];
      if (it == x0.end()) {
        EXPECT_EQ(r + rl, 0.0) << "R or RL off the cell at t = " << t;
        continue;
      }
      total += r + rl;
      bound += rl;
      const double rx = it->second[0] - kCx, ry = it->second[1] - kCy;
      const double qx = c * rx - s * ry, qy = s * rx + c * ry;
      double dx = f.column("x")[i] - (kCx + kV * t + qx);
      dx -= 2.0 * std::round(dx / 2.0);  // periodic along x, length 2
      const double dy = f.column("y")[i] - (kCy + qy);
      worst_x = std::max({worst_x, std::fabs(dx), std::fabs(dy)});
      worst_v = std::max({worst_v, std::fabs(f.column("vx")[i] - (kV - kW * qy)),
                          std::fabs(f.column("vy")[i] - kW * qx)});
    }
    if (k == 0) total0 = total;
    EXPECT_EQ(total, total0) << "R + RL at t = " << t;
    if (k + 1 == fr.size()) {
      std::printf("RESULT moving_body_e2e t=%g bound RL=%g of R+RL=%g\n", t, bound, total);
      EXPECT_GT(bound, 0.0) << "no binding on the moving membrane";
    }
  }
  std::printf("RESULT moving_body_e2e max |x - closed form| %.3g, |v - closed form| %.3g\n",
              worst_x, worst_v);
  EXPECT_LT(worst_x, 1e-9);
  EXPECT_LT(worst_v, 1e-9);
  EXPECT_GT(total0, 0.0);

  // stopped at t = 0.5 and resumed: the same frames
  ASSERT_EQ(run(bin("sadr") + " run " + scene.string() + " -q --embedded --stop-at 0.5 -o " +
                    (d / "resumed").string(),
                d / "stop.log"),
            0)
      << read_file(d / "stop.log");
  ASSERT_EQ(
      run(bin("sadr") + " resume " + (d / "resumed").string() + " -q --embedded", d / "resume.log"),
      0)
      << read_file(d / "resume.log");
  expect_same_frames(d / "out", d / "resumed");

  ASSERT_EQ(run(bin("sadr") + " summary " + (d / "out").string(), d / "summary.log"), 0);
  const std::string summary = read_file(d / "summary.log");
  EXPECT_NE(summary.find("fluid inside walls: none"), std::string::npos) << summary;
}

TEST(MovingBodyE2e, LoaderRefusesMorrisWallsOnATurningBody) {
  const fs::path d = scratch("moving-body-refused");
  const fs::path morris = write_scene(
      d, replace_once(kScene, "wall_model: adami", "wall_model: morris"), "morris.yaml");
  ASSERT_NE(run(bin("sadr") + " validate " + morris.string(), d / "a.log"), 0);
  EXPECT_NE(read_file(d / "a.log").find("a moving body with fluid.wall_model morris that turns"),
            std::string::npos)
      << read_file(d / "a.log");
}

}  // namespace
}  // namespace sadr::e2e
