// SPDX-License-Identifier: MIT
// "Swapping fluid backends" end to end: the shipped example
// examples/poiseuille_tracer_2d.yaml (SDPD fluid, stochastic tracer on the
// particle graph) runs through `sadr run` with child services, and the same
// file with only `backend: sdpd` replaced by `backend: tdpd` (and a shorter end
// time, for the test's run time) runs too. For both: exit 0, the plan names
// the backend, the tracer count (8000 molecules, no reactions, no-flux walls)
// is exactly conserved in every frame, and the body force drives the fluid and
// the tracer-carrying particles downstream (+x). WallModel.*: the scene's fluid.wall_model
// reaches the backend.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "cli_test_support.hpp"

namespace sadr::e2e {
namespace {

class BackendSwap : public ::testing::TestWithParam<const char*> {};

TEST_P(BackendSwap, PoiseuilleTracerExampleRunsWithOnlyTheBackendNameChanged) {
  const std::string backend = GetParam();
  const fs::path d = scratch(std::string("swap-") + backend);
  std::string text =
      read_file(fs::path(SADR_SOURCE_DIR) / "examples" / "poiseuille_tracer_2d.yaml");
  text = replace_once(text, "backend: sdpd", "backend: " + backend);
  text = replace_once(text, "end: 10.0", "end: 2.0");
  const fs::path scene = write_scene(d, text);
  ASSERT_EQ(
      run(bin("sadr") + " run " + scene.string() + " --no-progress -o " + (d / "out").string(),
          d / "run.log"),
      0)
      << read_file(d / "run.log");
  EXPECT_NE(read_file(d / "out" / "run.json").find("\"fluid_backend\": \"" + backend + "\""),
            std::string::npos);
  EXPECT_NE(read_file(d / "run.log").find("fluid_service (" + backend + ")"), std::string::npos);
  const auto all = frames(d / "out");
  ASSERT_EQ(all.size(), 10u);  // t = 0, 0.5, ..., 2.0 as vtu + csv
  for (const auto& p : all) {
    if (p.extension() != ".csv") continue;
    const CsvFrame f = read_csv(p);
    double total = 0;
    for (double n : f.column("T")) total += n;
    EXPECT_EQ(total, 8000.0) << p;
  }
  const CsvFrame last = read_csv(all.back().extension() == ".csv" ? all.back() : all.end()[-2]);
  const auto& kind = last.column("kind");
  const auto& vx = last.column("vx");
  const auto& tracer = last.column("T");
  double fluid_vx = 0, fluid_n = 0, tracer_vx = 0, tracer_n = 0;
  for (std::size_t i = 0; i < last.rows(); ++i) {
    if (kind[i] != 0) continue;
    fluid_vx += vx[i], fluid_n += 1;
    tracer_vx += tracer[i] * vx[i], tracer_n += tracer[i];
  }
  fluid_vx /= fluid_n;
  tracer_vx /= tracer_n;
  std::printf("%s: mean fluid vx %.4f, tracer-weighted vx %.4f at t = 2\n", backend.c_str(),
              fluid_vx, tracer_vx);
  // Start-up flow at t = 2 = 0.2 H^2/nu: the mean speed is a good fraction of
  // the steady 2/3 u_max = 0.067 for SDPD; tDPD's own viscosity differs, so
  // only the direction and a clear magnitude are asserted.
  EXPECT_GT(fluid_vx, 0.01);
  EXPECT_GT(tracer_vx, 0.01);
  if (!HasFailure()) fs::remove_all(d);  // keep the evidence of a failure
}

INSTANTIATE_TEST_SUITE_P(SdpdAndTdpd, BackendSwap, ::testing::Values("sdpd", "tdpd"));

/// Mean vx of the fluid particles in the last csv frame of a run of the Poiseuille example to
/// t = 2 with `fluid_extra` added to its fluid section.
double mean_fluid_vx_at_t2(const std::string& name, const std::string& fluid_extra) {
  const fs::path d = scratch("wall-" + name);
  std::string text =
      read_file(fs::path(SADR_SOURCE_DIR) / "examples" / "poiseuille_tracer_2d.yaml");
  text = replace_once(text, "  backend: sdpd\n", "  backend: sdpd\n" + fluid_extra);
  text = replace_once(text, "end: 10.0", "end: 2.0");
  const fs::path scene = write_scene(d, text);
  EXPECT_EQ(
      run(bin("sadr") + " run " + scene.string() + " --no-progress -o " + (d / "out").string(),
          d / "run.log"),
      0)
      << read_file(d / "run.log");
  const auto all = frames(d / "out");
  if (all.empty()) return 0.0;
  const CsvFrame last = read_csv(all.back().extension() == ".csv" ? all.back() : all.end()[-2]);
  double vx = 0, n = 0;
  for (std::size_t i = 0; i < last.rows(); ++i) {
    if (last.column("kind")[i] != 0) continue;
    vx += last.column("vx")[i], n += 1;
  }
  if (!::testing::Test::HasFailure()) fs::remove_all(d);
  return vx / n;
}

// fluid.wall_model: morris (with the wall planes at y = 0 and 1, half a spacing outside the
// fluid rows) reaches the SDPD backend: Morris' extrapolated wall velocity puts the no-slip
// planes at y = 0, 1, while stationary wall particles act at y = -0.032, 1.032 (the example's
// header), so the channel is narrower and the start-up flow slower at the same body force.
TEST(WallModel, MorrisWallsFromTheSceneSlowTheChannelFlow) {
  const double stationary = mean_fluid_vx_at_t2("stationary", "");
  const double morris =
      mean_fluid_vx_at_t2("morris",
                          "  wall_model: morris\n"
                          "  wall_planes:\n"
                          "    - {region: lower_wall, point: [0.0, 0.0], normal: [0.0, 1.0]}\n"
                          "    - {region: upper_wall, point: [0.0, 1.0], normal: [0.0, -1.0]}\n");
  std::printf("mean fluid vx at t = 2: stationary %.5f, morris %.5f (ratio %.4f)\n", stationary,
              morris, morris / stationary);
  EXPECT_GT(stationary, 0.01);
  EXPECT_GT(morris, 0.01);
  EXPECT_LT(morris, 0.99 * stationary);
}

// fluid.wall_model: adami (Adami, Hu & Adams 2012) reaches the SDPD backend without wall planes:
// the wall velocity 2 v_wall - <v_f> puts the no-slip planes midway between the fluid and the
// wall rows (y = 0, 1), so, as with Morris walls, the start-up flow is slower than with stationary
// wall particles.
TEST(WallModel, AdamiWallsFromTheSceneSlowTheChannelFlow) {
  const double stationary = mean_fluid_vx_at_t2("stationary-a", "");
  const double adami = mean_fluid_vx_at_t2("adami", "  wall_model: adami\n");
  std::printf("mean fluid vx at t = 2: stationary %.5f, adami %.5f (ratio %.4f)\n", stationary,
              adami, adami / stationary);
  EXPECT_GT(adami, 0.01);
  EXPECT_LT(adami, 0.99 * stationary);
}

}  // namespace
}  // namespace sadr::e2e
