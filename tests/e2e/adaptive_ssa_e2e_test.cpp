// SPDX-License-Identifier: MIT
// `ssa: {method: adaptive}` through `sadr run` (docs/scene-format.md `ssa`): a periodic 1D
// line of 32 static particles, 2000 molecules of A in each particle of the left half.
//  - the run succeeds; the plan line and run.json name the method and the tolerance;
//  - molecules are conserved in every frame (periodic, no reactions);
//  - it fires far fewer exact events than the exact method on the same scene (run.json
//    ssa_events; an event count, not a timing);
//  - the same frames, byte for byte, with ssa_service embedded and as a tcp service (the
//    method and tolerance cross the wire);
//  - `method: exact` written out gives the frames of the scene without an `ssa` section.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "cli_test_support.hpp"

namespace sadr::e2e {
namespace {

std::string scene(const std::string& ssa) {
  return R"(name: adaptive
dimension: 1
box: {lower: [0.0], upper: [1.0], periodic: [true]}
regions:
  - {name: left, shape: box, lower: [0.0], upper: [0.5]}
particles: {spacing: 0.03125}
fluid: {backend: static, h_over_dx: 2.0}
species:
  - {name: A, diffusivity: 0.002, initial: [{region: left, count: 2000}]}
time: {coupling_step: 0.25, end: 2.0}
output: {every: 1.0, formats: [csv]}
seed: 5
)" + ssa;
}

fs::path run_scene(const std::string& name, const std::string& text) {
  const fs::path d = scratch("adaptive-ssa-" + name);
  const fs::path s = write_scene(d, text);
  EXPECT_EQ(run(bin("sadr") + " run " + s.string() + " --no-progress --embedded -o " +
                    (d / "out").string(),
                d / "run.log"),
            0)
      << read_file(d / "run.log");
  return d;
}

nlohmann::json manifest(const fs::path& d) {
  return nlohmann::json::parse(read_file(d / "out" / "run.json"));
}

TEST(AdaptiveSsaE2e, RunsConservesAndFiresFewerExactEvents) {
  const fs::path a = run_scene("adaptive", scene("ssa: {method: adaptive, tolerance: 0.01}\n"));
  const fs::path e = run_scene("exact", scene(""));
  EXPECT_NE(read_file(a / "run.log").find("ssa method: adaptive, tolerance 0.01"),
            std::string::npos)
      << read_file(a / "run.log");
  const nlohmann::json ja = manifest(a), je = manifest(e);
  EXPECT_EQ(ja["plan"]["ssa_method"], "adaptive");
  EXPECT_EQ(ja["plan"]["ssa_tolerance"], 0.01);
  EXPECT_FALSE(je["plan"].contains("ssa_method"));  // the exact plan is unchanged
  const auto adaptive_events = ja["ssa_events"].get<std::uint64_t>();
  const auto exact_events = je["ssa_events"].get<std::uint64_t>();
  ASSERT_GT(exact_events, 100000u);
  EXPECT_LT(adaptive_events * 10, exact_events);
  RecordProperty("exact_events", std::to_string(exact_events));
  RecordProperty("adaptive_events", std::to_string(adaptive_events));
  int checked = 0;
  for (const auto& p : frames(a / "out")) {
    const CsvFrame f = read_csv(p);
    double total = 0;
    for (double x : f.column("A")) total += x;
    EXPECT_EQ(total, 16 * 2000.0) << p;
    ++checked;
  }
  EXPECT_EQ(checked, 3);
}

TEST(AdaptiveSsaE2e, SameFramesEmbeddedAndAsTcpService) {
  const std::string text = scene("ssa: {method: adaptive, tolerance: 0.05}\n");
  const fs::path a = run_scene("embedded", text);
  const fs::path d = scratch("adaptive-ssa-tcp");
  const fs::path s = write_scene(d, text);
  ASSERT_EQ(
      run_with_tcp_services(bin("sadr") + " run " + s.string() + " --no-progress ", d / "out"), 0)
      << read_file(d / "out.log");
  expect_same_frames(a / "out", d / "out");
}

TEST(AdaptiveSsaE2e, ExactWrittenOutIsTheDefault) {
  const fs::path a = run_scene("default", scene(""));
  const fs::path b = run_scene("exact-key", scene("ssa: {method: exact}\n"));
  expect_same_frames(a / "out", b / "out");
}

}  // namespace
}  // namespace sadr::e2e
