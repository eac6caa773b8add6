// SPDX-License-Identifier: MIT
// Forces on bodies (scene fluid.body_forces) end to end through `sadr run`: a body-force-driven
// periodic flow past a solid disk made by `geometry`, run to steady state. Checked: body_forces.csv
// has one row per coupling step with its t and dt, the last force on the disk equals the driving
// force on the fluid, g M (1 %: nothing else holds the fluid), the torque is zero, run.json
// summarises it, a stopped and resumed run writes the same file; the frames are byte-identical
// to the same run without the key; the scene loader refuses an unknown body and a region
// without wall particles.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "cli_test_support.hpp"

namespace sadr::e2e {
namespace {

constexpr double kG = 1.0;

const char* const kScene = R"(name: disk_forces
dimension: 2
box: {lower: [0.0, 0.0], upper: [1.0, 1.0], periodic: [true, true]}
geometry:
  spacing: 0.05
  bodies:
    - {name: disk, role: solid, shape: {type: disk, center: [0.5, 0.5], radius: 0.2}}
    - {name: left, role: region, shape: {type: box, lower: [0.0, 0.0], upper: [0.2, 1.0]}, kinds: [fluid]}
fluid:
  backend: sdpd
  h_over_dx: 3.0
  kernel: wendland_c2
  sound_speed: 10.0
  shear_viscosity: 1.0
  gravity: [1.0, 0.0]
  wall_model: adami
  body_forces: [disk]
time: {coupling_step: 0.05, end: 0.5}
output: {every: 0.25, formats: [csv]}
)";

struct Row {
  double t = 0, dt = 0;
  std::string body;
  double f[3] = {}, torque[3] = {};
};

std::vector<Row> read_forces(const fs::path& p, std::string& header) {
  std::istringstream in(read_file(p));
  std::vector<Row> rows;
  std::string line;
  std::getline(in, header);
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::string cell;
    std::vector<std::string> c;
    while (std::getline(s, cell, ',')) c.push_back(cell);
    if (c.size() != 9) continue;
    Row r;
    r.t = std::stod(c[0]);
    r.dt = std::stod(c[1]);
    r.body = c[2];
    for (int a = 0; a < 3; ++a) {
      r.f[a] = std::stod(c[3 + a]);
      r.torque[a] = std::stod(c[6 + a]);
    }
    rows.push_back(r);
  }
  return rows;
}

TEST(BodyForcesE2e, DiskHoldsTheDrivenFluidAndFramesAreUnchanged) {
  const fs::path d = scratch("body-forces");
  const fs::path scene = write_scene(d, kScene);
  ASSERT_EQ(
      run(bin("sadr") + " run " + scene.string() + " -q --embedded -o " + (d / "out").string(),
          d / "run.log"),
      0)
      << read_file(d / "run.log");
  std::string header;
  const auto rows = read_forces(d / "out" / "body_forces.csv", header);
  EXPECT_EQ(header, "t,dt,body,Fx,Fy,Fz,Tx,Ty,Tz");
  ASSERT_EQ(rows.size(), 10U);
  for (std::size_t k = 0; k < rows.size(); ++k) {
    EXPECT_EQ(rows[k].body, "disk");
    EXPECT_NEAR(rows[k].t, 0.05 * static_cast<double>(k + 1), 1e-12);
    EXPECT_NEAR(rows[k].dt, 0.05, 1e-12);
  }
  const auto fr = frames(d / "out");
  ASSERT_FALSE(fr.empty());
  const CsvFrame last = read_csv(fr.back());
  double mass = 0;
  for (std::size_t i = 0; i < last.rows(); ++i) {
    if (last.column("kind")[i] == 0) mass += last.column("mass")[i];
  }
  const Row& end = rows.back();
  const double mg = mass * kG;
  EXPECT_NEAR(end.f[0] / mg, 1.0, 0.01);
  EXPECT_NEAR(end.f[1] / mg, 0.0, 1e-3);
  EXPECT_NEAR(end.torque[2] / (mg * 0.2), 0.0, 1e-3);
  const std::string manifest = read_file(d / "out" / "run.json");
  EXPECT_NE(manifest.find("\"body_forces\""), std::string::npos);
  EXPECT_NE(manifest.find("\"mean_force\""), std::string::npos);
  std::printf("F_x / (M g) at t = 0.5: %.6f\n", end.f[0] / mg);
  ASSERT_EQ(run(bin("sadr") + " summary " + (d / "out").string(), d / "summary.log"), 0);
  const std::string summary = read_file(d / "summary.log");
  EXPECT_NE(summary.find("forces on bodies (body_forces.csv):"), std::string::npos) << summary;
  EXPECT_NE(summary.find("disk: F = (0.87"), std::string::npos) << summary;

  // stopped at t = 0.25 and resumed: the rows up to the checkpoint kept, the same file
  ASSERT_EQ(run(bin("sadr") + " run " + scene.string() + " -q --embedded --stop-at 0.25 -o " +
                    (d / "resumed").string(),
                d / "stop.log"),
            0)
      << read_file(d / "stop.log");
  ASSERT_EQ(
      run(bin("sadr") + " resume " + (d / "resumed").string() + " -q --embedded", d / "resume.log"),
      0)
      << read_file(d / "resume.log");
  EXPECT_TRUE(read_file(d / "resumed" / "body_forces.csv") ==
              read_file(d / "out" / "body_forces.csv"));

  // the same scene without the key: the same frames, no CSV
  const fs::path plain =
      write_scene(d, replace_once(kScene, "  body_forces: [disk]\n", ""), "plain.yaml");
  ASSERT_EQ(
      run(bin("sadr") + " run " + plain.string() + " -q --embedded -o " + (d / "plain").string(),
          d / "plain.log"),
      0)
      << read_file(d / "plain.log");
  EXPECT_FALSE(fs::exists(d / "plain" / "body_forces.csv"));
  expect_same_frames(d / "out", d / "plain");
}

TEST(BodyForcesE2e, LoaderRefusesUnknownBodiesAndRegionsWithoutWalls) {
  const fs::path d = scratch("body-forces-refused");
  const fs::path unknown =
      write_scene(d, replace_once(kScene, "body_forces: [disk]", "body_forces: [wheel]"), "a.yaml");
  ASSERT_NE(run(bin("sadr") + " validate " + unknown.string(), d / "a.log"), 0);
  EXPECT_NE(read_file(d / "a.log").find("unknown region 'wheel'"), std::string::npos)
      << read_file(d / "a.log");
  const fs::path fluid_only =
      write_scene(d, replace_once(kScene, "body_forces: [disk]", "body_forces: [left]"), "b.yaml");
  ASSERT_NE(run(bin("sadr") + " validate " + fluid_only.string(), d / "b.log"), 0);
  EXPECT_NE(read_file(d / "b.log").find("region 'left' holds no wall particle"), std::string::npos)
      << read_file(d / "b.log");
}

}  // namespace
}  // namespace sadr::e2e
