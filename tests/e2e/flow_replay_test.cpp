// SPDX-License-Identifier: MIT
// Flow replay end to end (flow_replay.hpp): an ensemble of the cell-in-channel
// example (a deterministic SDPD flow, stochastic binding on the cell) computes
// its fluid once and replays it; every frame, the .pvd index and the ensemble
// CSVs are byte-identical to the same ensemble with --no-flow-replay. A
// replayed ensemble stopped with --stop-at resumes to the same bytes, a
// corrupt flow replay file is refused loudly, two array tasks started together
// record the fluid once (under a lock) and replay it, and thermal noise turns
// replay off with the reason.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_test_support.hpp"
#include "sadr/orchestrator/checkpoint.hpp"

namespace sadr::orchestrator {
namespace {
namespace fs = std::filesystem;
using namespace sadr::e2e;

/// The example, 20 coupling steps (end 0.4) with a frame every 0.1.
std::string cell_scene(const std::string& fluid_extra = "") {
  std::string s =
      read_file(fs::path(SADR_SOURCE_DIR) / "examples" / "cell_in_channel_geometry_2d.yaml");
  s = replace_once(s, "  end: 2.0", "  end: 0.4");
  s = replace_once(s, "  every: 0.5", "  every: 0.1");
  return replace_once(s, "  backend: sdpd\n", "  backend: sdpd\n" + fluid_extra);
}

/// Every file under frames/ and ensemble/ of every realization, and the .pvd indexes,
/// relative to `dir`.
std::vector<fs::path> outputs(const fs::path& dir) {
  std::vector<fs::path> out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    const fs::path rel = fs::relative(e.path(), dir);
    const std::string s = rel.string();
    if (s.find("/frames/") != std::string::npos || s.rfind("ensemble/", 0) == 0 ||
        rel.extension() == ".pvd") {
      out.push_back(rel);
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

void expect_same_outputs(const fs::path& a, const fs::path& b, std::size_t realizations) {
  const auto fa = outputs(a), fb = outputs(b);
  ASSERT_EQ(fa, fb);
  // 5 frames (t = 0, 0.1, ..., 0.4) x (vtu + csv) + one .pvd per realization; 5 ensemble CSVs.
  EXPECT_EQ(fa.size(), realizations * 11 + 5);
  for (const auto& f : fa) {
    EXPECT_TRUE(read_file(a / f) == read_file(b / f)) << f << " differs";
  }
}

nlohmann::json run_json(const fs::path& p) {
  return nlohmann::json::parse(read_file(p / "run.json"));
}

TEST(FlowReplay, EnsembleFramesAreByteIdenticalWithAndWithoutReplay) {
  const fs::path d = scratch("flow-replay-same");
  const fs::path scene = write_scene(d, cell_scene());
  const std::string sadr = bin("sadr") + " run " + scene.string() + " --no-progress -r 3 -j 2 ";
  ASSERT_EQ(run(sadr + "-o " + (d / "replay").string(), d / "replay.log"), 0)
      << read_file(d / "replay.log");
  ASSERT_EQ(run(sadr + "--no-flow-replay -o " + (d / "step").string(), d / "step.log"), 0)
      << read_file(d / "step.log");
  const std::string log = read_file(d / "replay.log");
  EXPECT_NE(log.find("flow replay: on (the fluid is the same in every realization"),
            std::string::npos)
      << log;
  EXPECT_NE(read_file(d / "step.log").find("flow replay: off (--no-flow-replay)"),
            std::string::npos);
  EXPECT_TRUE(fs::exists(d / "replay" / "flow_replay.bin"));
  EXPECT_FALSE(fs::exists(d / "step" / "flow_replay.bin"));
  expect_same_outputs(d / "replay", d / "step", 3);
  // The realizations differ (else byte identity would prove little) ...
  const fs::path last = fs::path("frames") / "frame_000004.csv";
  EXPECT_FALSE(read_file(d / "step" / "realization_0000" / last) ==
               read_file(d / "step" / "realization_0001" / last));
  // ... and the replayed ones never stepped a fluid: no time inside a backend, the same
  // sub-step count as when they did.
  for (const char* r : {"realization_0000", "realization_0002"}) {
    const auto a = run_json(d / "replay" / r), b = run_json(d / "step" / r);
    EXPECT_EQ(a["plan"]["flow_replay"], true);
    EXPECT_EQ(b["plan"]["flow_replay"], false);
    EXPECT_EQ(a["timings_s"].value("fluid_compute", 0.0), 0.0) << r;
    EXPECT_GT(b["timings_s"].value("fluid_compute", 0.0), 0.0) << r;
    EXPECT_EQ(a["fluid_substeps"], b["fluid_substeps"]) << r;
    EXPECT_EQ(a["fluid_smallest_limit"], b["fluid_smallest_limit"]) << r;  // replayed too
    EXPECT_TRUE(a["fluid_smallest_limit"].contains("stable_time_step")) << r;
    EXPECT_GT(a["fluid_substeps"].get<int>(), 0) << r;
  }
}

TEST(FlowReplay, AStoppedReplayedEnsembleResumesToTheSameBytesAndACorruptFileIsRefused) {
  const fs::path d = scratch("flow-replay-resume");
  const fs::path scene = write_scene(d, cell_scene());
  const std::string sadr = bin("sadr") + " run " + scene.string() + " -q -r 2 -j 2 ";
  ASSERT_EQ(run(sadr + "--no-flow-replay -o " + (d / "step").string(), d / "step.log"), 0)
      << read_file(d / "step.log");
  ASSERT_EQ(run(sadr + "--stop-at 0.2 -o " + (d / "cut").string(), d / "cut.log"), 0)
      << read_file(d / "cut.log");
  // Each realization stopped at t = 0.2 with a checkpoint that is a place in the file.
  for (const char* r : {"realization_0000", "realization_0001"}) {
    const LoadedCheckpoint cp = load_checkpoint(d / "cut" / r / "checkpoint", "");
    EXPECT_EQ(cp.manifest.step_index, 10u);
    ASSERT_EQ(cp.blobs.count("fluid"), 1u);
    EXPECT_EQ(cp.blobs.at("fluid").bytes.rfind("sadr-flow-replay-position ", 0), 0u);
  }
  fs::copy(d / "cut", d / "broken", fs::copy_options::recursive);
  ASSERT_EQ(run(bin("sadr") + " resume " + (d / "cut").string() + " -q", d / "resume.log"), 0)
      << read_file(d / "resume.log");
  expect_same_outputs(d / "cut", d / "step", 2);

  // One flipped byte in the last record: the resumed realizations fail, naming it.
  const fs::path tape = d / "broken" / "flow_replay.bin";
  {
    std::fstream f(tape, std::ios::in | std::ios::out | std::ios::binary);
    const auto at = static_cast<std::streamoff>(fs::file_size(tape) - 200);
    f.seekg(at);
    const char c = static_cast<char>(f.get());
    f.seekp(at);
    f.put(static_cast<char>(c ^ 0x01));
  }
  const fs::path log = d / "broken.log";
  EXPECT_NE(run(bin("sadr") + " resume " + (d / "broken").string() + " -q --retries 0", log), 0);
  EXPECT_NE(read_file(log).find("checksum mismatch"), std::string::npos) << read_file(log);
}

TEST(FlowReplay, ArrayTasksStartedTogetherRecordTheFluidOnceAndReplayIt) {
  const fs::path d = scratch("flow-replay-array");
  const fs::path scene = write_scene(d, cell_scene());
  const std::string sadr = bin("sadr") + " run " + scene.string() + " --no-progress ";
  ASSERT_EQ(run(sadr + "-q -r 2 -j 2 --no-flow-replay -o " + (d / "step").string(), d / "step.log"),
            0)
      << read_file(d / "step.log");
  // Two tasks of one array at once: one records DIR/flow_replay.bin under the lock, the
  // other waits for it; both replay it.
  const std::string task = sadr + "-o " + (d / "array").string() + " --realization ";
  ASSERT_EQ(run("(" + task + "0 > " + (d / "t0.log").string() + " 2>&1 & " + task + "1 > " +
                    (d / "t1.log").string() + " 2>&1; r1=$?; wait $!; r0=$?; exit $((r0 + r1)))",
                d / "array.log"),
            0)
      << read_file(d / "t0.log") << read_file(d / "t1.log");
  const std::string logs = read_file(d / "t0.log") + read_file(d / "t1.log");
  EXPECT_NE(logs.find("flow replay: on (array task:"), std::string::npos) << logs;
  std::size_t recorded = 0;
  for (auto at = logs.find("computing the fluid once"); at != std::string::npos;
       at = logs.find("computing the fluid once", at + 1)) {
    ++recorded;
  }
  EXPECT_EQ(recorded, 1u) << logs;
  EXPECT_TRUE(fs::exists(d / "array" / "flow_replay.bin"));
  for (const char* r : {"realization_0000", "realization_0001"}) {
    EXPECT_EQ(run_json(d / "array" / r)["plan"]["flow_replay"], true) << r;
    EXPECT_EQ(run_json(d / "array" / r)["timings_s"].value("fluid_compute", 0.0), 0.0) << r;
    for (const char* f : {"frame_000004.csv", "frame_000004.vtu", "frame_000000.csv"}) {
      EXPECT_TRUE(read_file(d / "array" / r / "frames" / f) ==
                  read_file(d / "step" / r / "frames" / f))
          << r << "/" << f;
    }
  }
}

TEST(FlowReplay, ThermalNoiseTurnsItOffWithTheReason) {
  const fs::path d = scratch("flow-replay-noise");
  std::string text = cell_scene("  temperature: 1.0e-6\n");
  text = replace_once(text, "  end: 0.4", "  end: 0.04");
  text = replace_once(text, "  every: 0.1", "  every: 0.04");
  const fs::path scene = write_scene(d, text);
  const fs::path out = d / "out";
  ASSERT_EQ(
      run(bin("sadr") + " run " + scene.string() + " --no-progress -r 2 -j 2 -o " + out.string(),
          d / "run.log"),
      0)
      << read_file(d / "run.log");
  const std::string log = read_file(d / "run.log");
  EXPECT_NE(log.find("flow replay: off (thermal noise on: k_B T > 0, the fluid draws random "
                     "numbers)"),
            std::string::npos)
      << log;
  EXPECT_FALSE(fs::exists(out / "flow_replay.bin"));
  const auto j = run_json(out / "realization_0001");
  EXPECT_EQ(j["plan"]["flow_replay"], false);
  EXPECT_GT(j["timings_s"].value("fluid_compute", 0.0), 0.0);
}

}  // namespace
}  // namespace sadr::orchestrator
