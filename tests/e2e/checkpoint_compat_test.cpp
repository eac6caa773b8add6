// SPDX-License-Identifier: MIT
// A checkpoint written by an older build resumes bit-identically on this one.
// Each fixture holds a checkpoint written at t = 0.5 by an older build and the
// frame at t = 1 of an uninterrupted run of that build; resuming it here must
// give that frame byte for byte:
//  - tests/data/checkpoint_v1: a moving SDPD + SSA scene (Poiseuille tracer)
//    by the session-start build 263b868 (before the typed clients, the split
//    loop and the one-round-trip back-transfer);
//  - tests/data/checkpoint_open_v1: an SDPD open channel (inlet conveyor,
//    outlet recycling, a stochastic tracer fed at the inlet) by 6ab505a
//    (before the open boundary travelled as the typed FluidModel.open_boundary;
//    its fluid blob carries the channel's conveyor state).
// (tests/e2e/compare_builds.py --resume does the same for every example
// against any two builds.)
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

#include "cli_test_support.hpp"

namespace sadr::e2e {
namespace {

/// Resumes the fixture tests/data/<name> and compares its frame at t = 1.
void resume_matches_the_old_build(const std::string& name) {
  const fs::path fixture = fs::path(SADR_SOURCE_DIR) / "tests/data" / name;
  const fs::path d = scratch(name);
  fs::create_directories(d / "out");
  fs::copy_file(fixture / "scene.yaml", d / "scene.yaml");
  fs::copy(fixture / "checkpoint", d / "out" / "checkpoint");
  // The manifest names the scene by absolute path: point it at the copy (its
  // hash, checked on resume, is that of the fixture's bytes).
  const fs::path manifest = d / "out" / "checkpoint" / "checkpoint.json";
  nlohmann::json j = nlohmann::json::parse(read_file(manifest));
  j["scene_path"] = (d / "scene.yaml").string();
  std::ofstream(manifest) << j.dump(2);
  ASSERT_EQ(
      run(bin("sadr") + " resume " + (d / "out" / "checkpoint").string() + " -q", d / "resume.log"),
      0)
      << read_file(d / "resume.log");
  const std::string got = read_file(d / "out" / "frames" / "frame_000002.csv");
  const std::string want = read_file(fixture / "expected" / "frame_000002.csv");
  ASSERT_FALSE(want.empty());
  EXPECT_TRUE(got == want) << "the frame at t = 1 after resuming differs from the old build's";
  if (!::testing::Test::HasFailure()) fs::remove_all(d);
}

TEST(CheckpointCompat, ACheckpointOfTheSessionStartBuildResumesBitIdentically) {
  resume_matches_the_old_build("checkpoint_v1");
}

TEST(CheckpointCompat, AnOpenChannelCheckpointOfTheUntypedOpenBoundaryBuildResumesBitIdentically) {
  resume_matches_the_old_build("checkpoint_open_v1");
}

}  // namespace
}  // namespace sadr::e2e
