// SPDX-License-Identifier: MIT
// Flow replay in a sweep (docs/sweeps.md): the runs of a sweep over a stochastic
// reaction's rate share one fluid, recorded once into SWEEP_DIR/flows/<key>.bin by
// the first run and replayed by all; their frames are byte-identical to the same
// sweep with --no-flow-replay. A sweep over a fluid parameter records one file per
// fluid. A lost file (a recorder that died, leaving only its partial file) is
// recorded again when failed runs are rerun.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "cli_test_support.hpp"

namespace sadr::orchestrator {
namespace {
namespace fs = std::filesystem;
using namespace sadr::e2e;

/// The cell-in-channel example (deterministic SDPD flow, stochastic binding on the cell),
/// 10 coupling steps (end 0.2) with a frame every 0.1.
std::string cell_scene() {
  std::string s =
      read_file(fs::path(SADR_SOURCE_DIR) / "examples" / "cell_in_channel_geometry_2d.yaml");
  s = replace_once(s, "  end: 2.0", "  end: 0.2");
  return replace_once(s, "  every: 0.5", "  every: 0.1");
}

fs::path write_sweep(const fs::path& d, const std::string& parameters, int realizations) {
  const fs::path p = d / "sweep.yaml";
  std::ofstream(p) << "scene: scene.yaml\nrealizations: " << realizations
                   << "\nseed: 4\nkeep: all\nexecutor: {type: local, workers: 2}\n"
                   << "parameters:\n  grid:\n    " << parameters << "\n";
  return p;
}

int sweep(const fs::path& file, const fs::path& out, const fs::path& log,
          const std::string& extra = "") {
  return run(bin("sadr") + " sweep " + file.string() + " -o " + out.string() + " " + extra, log);
}

nlohmann::json json_of(const fs::path& p) {
  return nlohmann::json::parse(read_file(p));
}

std::vector<fs::path> tapes(const fs::path& sweep_dir) {
  std::vector<fs::path> out;
  if (!fs::exists(sweep_dir / "flows")) return out;
  for (const auto& e : fs::directory_iterator(sweep_dir / "flows")) {
    if (e.path().extension() == ".bin") out.push_back(e.path());
  }
  return out;
}

/// Per fluid key: how many runs replayed it and how many recorded it.
std::map<std::string, std::pair<int, int>> replays_by_key(const fs::path& sweep_dir) {
  std::map<std::string, std::pair<int, int>> out;
  const auto m = json_of(sweep_dir / "sweep.json");
  for (const auto& r : m["runs"]) {
    const auto res = json_of(sweep_dir / r["dir"].get<std::string>() / "result.json");
    EXPECT_EQ(res["state"], "ok") << res.dump();
    if (!res.value("flow_replay", false)) continue;
    auto& [replayed, recorded] = out[res["fluid_key"].get<std::string>()];
    ++replayed;
    recorded += res.value("flow_recorded", false) ? 1 : 0;
  }
  return out;
}

void expect_same_run_frames(const fs::path& a, const fs::path& b, std::size_t runs) {
  const auto m = json_of(a / "sweep.json");
  ASSERT_EQ(m["runs"].size(), runs);
  for (const auto& r : m["runs"]) {
    const std::string dir = r["dir"].get<std::string>();
    const auto fa = frames(a / dir);
    EXPECT_EQ(fa.size(), 6u) << dir;  // t = 0, 0.1, 0.2 x (vtu + csv)
    expect_same_frames(a / dir, b / dir);
  }
}

TEST(SweepFlowReplay, AStochasticRateSweepRecordsTheFluidOnceAndReplaysItToEveryRun) {
  const fs::path d = scratch("sweep-flow-replay-rate");
  write_scene(d, cell_scene());
  const fs::path file = write_sweep(d, "reactions[binding].rate: [0.05, 0.5]", 2);
  ASSERT_EQ(sweep(file, d / "replay", d / "replay.log"), 0) << read_file(d / "replay.log");
  ASSERT_EQ(sweep(file, d / "step", d / "step.log", "--no-flow-replay"), 0)
      << read_file(d / "step.log");
  const std::string log = read_file(d / "replay.log");
  EXPECT_NE(log.find("point 1: flow replay: on (the fluid is the same in 4 runs (points 0 1)"),
            std::string::npos)
      << log;
  EXPECT_NE(read_file(d / "step.log").find("point 0: flow replay: off (--no-flow-replay)"),
            std::string::npos);
  // One file, recorded by one run, replayed by all four; none without replay.
  EXPECT_EQ(tapes(d / "replay").size(), 1u);
  EXPECT_TRUE(tapes(d / "step").empty());
  const auto keys = replays_by_key(d / "replay");
  ASSERT_EQ(keys.size(), 1u);
  EXPECT_EQ(keys.begin()->second, std::make_pair(4, 1));
  EXPECT_EQ(tapes(d / "replay").front().filename().string(),
            keys.begin()->first.substr(keys.begin()->first.find(':') + 1) + ".bin");
  EXPECT_TRUE(replays_by_key(d / "step").empty());
  const auto m = json_of(d / "replay" / "sweep.json");
  EXPECT_EQ(m["points"][0]["flow_replay"]["fluid_key"], m["points"][1]["flow_replay"]["fluid_key"]);
  EXPECT_EQ(m["points"][1]["flow_replay"]["on"], true);
  // No replayed run stepped a fluid; every run without replay did.
  for (const char* r : {"runs/p0000_r0000", "runs/p0001_r0001"}) {
    const auto a = json_of(d / "replay" / r / "run.json"), b = json_of(d / "step" / r / "run.json");
    EXPECT_EQ(a["plan"]["flow_replay"], true) << r;
    EXPECT_EQ(a["timings_s"].value("fluid_compute", 0.0), 0.0) << r;
    EXPECT_GT(b["timings_s"].value("fluid_compute", 0.0), 0.0) << r;
    EXPECT_EQ(a["fluid_substeps"], b["fluid_substeps"]) << r;
  }
  expect_same_run_frames(d / "replay", d / "step", 4);
  // The runs differ (else byte identity would prove little).
  const fs::path last = fs::path("frames") / "frame_000002.csv";
  EXPECT_FALSE(read_file(d / "step" / "runs/p0000_r0000" / last) ==
               read_file(d / "step" / "runs/p0001_r0000" / last));

  // A recorder that died left only its partial file: rerunning failed runs records the file
  // again (one run) and replays it, to the same bytes.
  fs::copy(d / "replay", d / "lost", fs::copy_options::recursive);
  const fs::path tape = tapes(d / "lost").front();
  fs::rename(tape, fs::path(tape.string() + ".partial"));
  for (const char* r : {"runs/p0000_r0001", "runs/p0001_r0000"}) {  // failed, nothing kept
    for (const char* sub : {"frames", "checkpoint"}) fs::remove_all(d / "lost" / r / sub);
    std::ofstream(d / "lost" / r / "result.json")
        << R"({"state": "failed", "exit_code": 3, "reason": "killed", "scene_hash": ""})";
  }
  ASSERT_EQ(run(bin("sadr") + " sweep --resume " + (d / "lost").string(), d / "lost.log"), 0)
      << read_file(d / "lost.log");
  EXPECT_NE(read_file(d / "lost.log").find("executed 2 runs, skipped 2 finished"),
            std::string::npos)
      << read_file(d / "lost.log");
  EXPECT_TRUE(fs::exists(tape));
  int recorded = 0;
  for (const char* r : {"runs/p0000_r0001", "runs/p0001_r0000"}) {
    const auto res = json_of(d / "lost" / r / "result.json");
    EXPECT_EQ(res["flow_replay"], true) << r;
    recorded += res["flow_recorded"].get<bool>() ? 1 : 0;
    expect_same_frames(d / "lost" / r, d / "step" / r);
  }
  EXPECT_EQ(recorded, 1);
  if (!HasFailure()) fs::remove_all(d);
}

TEST(SweepFlowReplay, AFluidParameterSweepRecordsOneFilePerFluid) {
  const fs::path d = scratch("sweep-flow-replay-viscosity");
  write_scene(d, cell_scene());
  // One realization per point: no fluid is shared, nothing to replay (a dry run says why).
  const fs::path single = write_sweep(d, "fluid.shear_viscosity: [0.1, 0.2]", 1);
  ASSERT_EQ(sweep(single, d / "dry", d / "dry.log", "--dry-run"), 0) << read_file(d / "dry.log");
  EXPECT_NE(read_file(d / "dry.log")
                .find("flow replay: off (no other run of the sweep has this "
                      "fluid)"),
            std::string::npos)
      << read_file(d / "dry.log");
  // Two realizations per point: each point's fluid recorded once, two files.
  const fs::path file = write_sweep(d, "fluid.shear_viscosity: [0.1, 0.2]", 2);
  ASSERT_EQ(sweep(file, d / "replay", d / "replay.log"), 0) << read_file(d / "replay.log");
  const std::string log = read_file(d / "replay.log");
  EXPECT_NE(log.find("point 0: flow replay: on (the fluid is the same in 2 runs (point 0)"),
            std::string::npos)
      << log;
  EXPECT_EQ(tapes(d / "replay").size(), 2u);
  const auto keys = replays_by_key(d / "replay");
  ASSERT_EQ(keys.size(), 2u);
  for (const auto& [key, counts] : keys) EXPECT_EQ(counts, std::make_pair(2, 1)) << key;
  const auto m = json_of(d / "replay" / "sweep.json");
  EXPECT_NE(m["points"][0]["flow_replay"]["fluid_key"], m["points"][1]["flow_replay"]["fluid_key"]);
  if (!HasFailure()) fs::remove_all(d);
}

}  // namespace
}  // namespace sadr::orchestrator
