// SPDX-License-Identifier: MIT
// A scene whose particles come from its `geometry` section, end to end:
// examples/cell_in_channel_geometry_2d.yaml (an SDPD channel with an elliptic
// cell, receptors on its membrane) through `sadr run`, and `sadr geometry` on
// the same scene. Checked: the run's particles are the ones `sadr geometry`
// writes (count, kinds, positions at t = 0), the membrane region holds every
// receptor (R + RL per membrane particle stays at its initial 20: diffusivity
// 0, so binding only converts one into the other), binding happened, and wall
// particles never move.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "cli_test_support.hpp"

namespace sadr::e2e {
namespace {

TEST(GeometryE2e, CellInChannelRunsAndKeepsItsReceptorsOnTheMembrane) {
  const fs::path d = scratch("geometry-cell");
  std::string text =
      read_file(fs::path(SADR_SOURCE_DIR) / "examples" / "cell_in_channel_geometry_2d.yaml");
  text = replace_once(text, "end: 2.0", "end: 0.5");
  text = replace_once(text, "every: 0.5", "every: 0.25");
  const fs::path scene = write_scene(d, text);
  ASSERT_EQ(run(bin("sadr") + " geometry " + scene.string() + " -o " + (d / "geo").string(),
                d / "geometry.log"),
            0)
      << read_file(d / "geometry.log");
  const std::string summary = read_file(d / "geometry.log");
  EXPECT_NE(summary.find("particles: 1040 (fluid 764, wall 276)"), std::string::npos) << summary;
  EXPECT_NE(summary.find("exact 1.905752"), std::string::npos) << summary;
  const CsvFrame g = read_csv(d / "geo" / "particles.csv");
  const auto& membrane = g.column("region_membrane");

  ASSERT_EQ(
      run(bin("sadr") + " run " + scene.string() + " -q --embedded -o " + (d / "out").string(),
          d / "run.log"),
      0)
      << read_file(d / "run.log");
  const auto files = frames(d / "out");
  std::size_t checked = 0;
  double bound_at_end = 0;
  for (const auto& p : files) {
    if (p.extension() != ".csv") continue;
    const CsvFrame f = read_csv(p);
    ASSERT_EQ(f.rows(), g.rows()) << p;
    const auto& kind = f.column("kind");
    const auto& x = f.column("x");
    const auto& y = f.column("y");
    const auto& r = f.column("R");
    const auto& rl = f.column("RL");
    double bound = 0;
    for (std::size_t i = 0; i < f.rows(); ++i) {
      EXPECT_EQ(kind[i], g.column("kind")[i]);
      if (kind[i] == 1) {  // walls stay where geometry put them
        EXPECT_EQ(x[i], g.column("x")[i]);
        EXPECT_EQ(y[i], g.column("y")[i]);
      }
      if (membrane[i] == 1) {
        EXPECT_EQ(r[i] + rl[i], 20.0) << p << " particle " << i;
        ++checked;
      } else {
        EXPECT_EQ(r[i] + rl[i], 0.0) << p << " particle " << i;
      }
      bound += rl[i];
    }
    bound_at_end = bound;
  }
  EXPECT_GT(checked, 0U);
  EXPECT_GT(bound_at_end, 0.0);
  std::printf("membrane particle-frames checked: %zu; RL at t = 0.5: %.0f\n", checked,
              bound_at_end);
}

}  // namespace
}  // namespace sadr::e2e
