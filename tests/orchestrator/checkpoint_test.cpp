// SPDX-License-Identifier: MIT
// Atomic writes under simulated crashes, checkpoint manifests, blob
// rotation, scene-hash and format-version refusal.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "sadr/common/status.hpp"
#include "sadr/orchestrator/atomic_file.hpp"
#include "sadr/orchestrator/checkpoint.hpp"
#include "sadr/orchestrator/hash.hpp"

namespace sadr::orchestrator {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  const fs::path d =
      fs::temp_directory_path() / ("sadr_ckpt_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::size_t file_count(const fs::path& dir) {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++n;
  return n;
}

TEST(AtomicFile, WritesAndReplaces) {
  const fs::path dir = fresh_dir("write");
  write_file_atomic(dir / "a.txt", "first");
  EXPECT_EQ(read_file_bytes(dir / "a.txt"), "first");
  write_file_atomic(dir / "a.txt", "second, longer");
  EXPECT_EQ(read_file_bytes(dir / "a.txt"), "second, longer");
  EXPECT_EQ(file_count(dir), 1U);  // no temporaries left behind
  fs::remove_all(dir);
}

TEST(AtomicFile, CrashMidWriteKeepsThePreviousFile) {
  const fs::path dir = fresh_dir("crash");
  const std::string old_bytes(1000, 'o');
  write_file_atomic(dir / "state", old_bytes);
  const std::string new_bytes(5000, 'n');
  AtomicWriteFault fault;
  fault.fail_after_bytes = 2500;
  EXPECT_THROW(write_file_atomic(dir / "state", new_bytes, &fault), IoError);
  EXPECT_EQ(read_file_bytes(dir / "state"), old_bytes);
  fault = AtomicWriteFault{};
  fault.fail_before_rename = true;
  EXPECT_THROW(write_file_atomic(dir / "state", new_bytes, &fault), IoError);
  EXPECT_EQ(read_file_bytes(dir / "state"), old_bytes);
  // Stale temporaries from the "crashes" do not disturb the next write.
  write_file_atomic(dir / "state", new_bytes);
  EXPECT_EQ(read_file_bytes(dir / "state"), new_bytes);
  fs::remove_all(dir);
}

TEST(AtomicFile, MissingDirectoryIsAnIoErrorNamingThePath) {
  try {
    write_file_atomic("/nonexistent_sadr_dir/x.txt", "x");
    FAIL() << "no exception";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent_sadr_dir"), std::string::npos) << e.what();
  }
}

CheckpointManifest base_manifest(std::uint64_t step, double time) {
  CheckpointManifest m;
  m.sadr_version = "0.1.0";
  m.scene_path = "examples/x.yaml";
  m.scene_hash = content_hash("scene bytes");
  m.seed = 12345;
  m.realization = 2;
  m.step_index = step;
  m.time = time;
  return m;
}

TEST(Checkpoint, RoundTripIsExact) {
  const fs::path dir = fresh_dir("roundtrip");
  std::string binary("\0\x01\xff blob", 8);
  const double t = 0.1 + 0.2;  // not representable in short decimal
  write_checkpoint(dir, base_manifest(7, t),
                   {{"fluid", {"sdpd", binary}}, {"ssa", {"nsm", "ssa state"}}});
  const auto loaded = load_checkpoint(dir, content_hash("scene bytes"));
  EXPECT_EQ(loaded.manifest.step_index, 7U);
  EXPECT_EQ(loaded.manifest.time, t);  // bit-exact through time_hex
  EXPECT_EQ(loaded.manifest.seed, 12345U);
  EXPECT_EQ(loaded.manifest.realization, 2U);
  EXPECT_EQ(loaded.manifest.format_version, kCheckpointFormatVersion);
  ASSERT_EQ(loaded.blobs.size(), 2U);
  EXPECT_EQ(loaded.blobs.at("fluid").bytes, binary);
  EXPECT_EQ(loaded.blobs.at("fluid").backend, "sdpd");
  EXPECT_EQ(loaded.blobs.at("ssa").bytes, "ssa state");
  // Loading by the manifest path works too.
  EXPECT_EQ(load_checkpoint(dir / kCheckpointManifestName, "").manifest.step_index, 7U);
  fs::remove_all(dir);
}

TEST(Checkpoint, DifferentSceneHashIsRefusedClearly) {
  const fs::path dir = fresh_dir("hash");
  write_checkpoint(dir, base_manifest(1, 0.5), {{"ssa", {"nsm", "x"}}});
  try {
    (void)load_checkpoint(dir, content_hash("another scene"));
    FAIL() << "no exception";
  } catch (const InvalidArgument& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("was written for a different scene"), std::string::npos) << msg;
    EXPECT_NE(msg.find(content_hash("scene bytes")), std::string::npos) << msg;
    EXPECT_NE(msg.find(content_hash("another scene")), std::string::npos) << msg;
  }
  fs::remove_all(dir);
}

TEST(Checkpoint, OtherFormatVersionIsRefused) {
  const fs::path dir = fresh_dir("version");
  write_checkpoint(dir, base_manifest(1, 0.5), {});
  auto j = nlohmann::json::parse(read_file_bytes(dir / kCheckpointManifestName));
  j["format_version"] = 99;
  write_file_atomic(dir / kCheckpointManifestName, j.dump());
  try {
    (void)load_checkpoint(dir, "");
    FAIL() << "no exception";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("format version 99"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

TEST(Checkpoint, CorruptBlobIsDetected) {
  const fs::path dir = fresh_dir("corrupt");
  const auto m = write_checkpoint(dir, base_manifest(3, 1.0), {{"ssa", {"nsm", "good bytes"}}});
  write_file_atomic(dir / m.blobs.at(0).file, "evil bytes");  // same size, other content
  EXPECT_THROW((void)load_checkpoint(dir, ""), InvalidArgument);
  fs::remove_all(dir);
}

TEST(Checkpoint, NewCheckpointReplacesOldOnlyWhenSafe) {
  const fs::path dir = fresh_dir("rotate");
  write_checkpoint(dir, base_manifest(10, 1.0), {{"ssa", {"nsm", "state at 10"}}});
  // A crash while writing the next checkpoint's blob: the old one still loads.
  AtomicWriteFault fault;
  fault.fail_after_bytes = 3;
  EXPECT_THROW(
      write_checkpoint(dir, base_manifest(20, 2.0), {{"ssa", {"nsm", "state at 20"}}}, &fault),
      IoError);
  auto loaded = load_checkpoint(dir, "");
  EXPECT_EQ(loaded.manifest.step_index, 10U);
  EXPECT_EQ(loaded.blobs.at("ssa").bytes, "state at 10");
  // A crash just before the manifest rename: the old one still loads.
  fault = AtomicWriteFault{};
  fault.fail_before_rename = true;
  EXPECT_THROW(
      write_checkpoint(dir, base_manifest(20, 2.0), {{"ssa", {"nsm", "state at 20"}}}, &fault),
      IoError);
  loaded = load_checkpoint(dir, "");
  EXPECT_EQ(loaded.manifest.step_index, 10U);
  EXPECT_EQ(loaded.blobs.at("ssa").bytes, "state at 10");
  // A clean write replaces it and deletes the old blob.
  write_checkpoint(dir, base_manifest(20, 2.0), {{"ssa", {"nsm", "state at 20"}}});
  loaded = load_checkpoint(dir, "");
  EXPECT_EQ(loaded.manifest.step_index, 20U);
  EXPECT_EQ(loaded.blobs.at("ssa").bytes, "state at 20");
  std::size_t blobs = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().extension() == ".blob") ++blobs;
  }
  // The step-10 blob is gone; the step-20 blob written before the simulated
  // manifest crash has the same name and bytes as the final one.
  EXPECT_EQ(blobs, 1U);
  fs::remove_all(dir);
}

TEST(Checkpoint, NotAManifestIsRefused) {
  const fs::path dir = fresh_dir("notmanifest");
  write_file_atomic(dir / "checkpoint.json", "{\"hello\": 1}");
  EXPECT_THROW((void)load_checkpoint(dir, ""), InvalidArgument);
  write_file_atomic(dir / "checkpoint.json", "not json");
  EXPECT_THROW((void)load_checkpoint(dir, ""), InvalidArgument);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace sadr::orchestrator
