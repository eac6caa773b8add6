// SPDX-License-Identifier: MIT
// A checkpoint written by an older build resumes bit-identically on this one:
// tests/data/checkpoint_v1 holds a checkpoint of a moving SDPD + SSA scene
// written at t = 0.5 by the session-start build 263b868 (before the typed
// clients, the split loop and the one-round-trip back-transfer), and the frame
// at t = 1 of an uninterrupted run of that build. Resuming it here must give
// that frame byte for byte. (tests/e2e/compare_builds.py --resume does the same
// for every example against any two builds.)
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

#include "cli_test_support.hpp"

namespace sadr::e2e {
namespace {

TEST(CheckpointCompat, ACheckpointOfTheSessionStartBuildResumesBitIdentically) {
  const fs::path fixture = fs::path(SADR_SOURCE_DIR) / "tests/data/checkpoint_v1";
  const fs::path d = scratch("checkpoint-v1");
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
  if (!HasFailure()) fs::remove_all(d);
}

}  // namespace
}  // namespace sadr::e2e
