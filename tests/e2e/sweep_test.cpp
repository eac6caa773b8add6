// SPDX-License-Identifier: MIT
// Scene overrides end to end (`sadr run --set`, run.json, resume), and sweeps.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include "cli_test_support.hpp"
#include "sweep_test_support.hpp"

namespace sadr::orchestrator {
namespace {
namespace fs = std::filesystem;
using namespace sadr::e2e;

TEST(SceneOverrideCli, RunRecordsOverridesAndResumesWithThem) {
  const fs::path d = scratch("override");
  const fs::path scene =
      write_scene(d, birth_death_scene(8, 400.0, 1.0, 0.4, "[0.1, 0.2, 0.3, 0.4]", "[csv]"));
  const std::string sadr = bin("sadr") + " run " + scene.string() + " -q ";
  const std::string set = " --set reactions[birth].rate=800 --set 'output.checkpoint_every=0.1'";
  ASSERT_EQ(run(sadr + "-o " + (d / "base").string(), d / "a.log"), 0) << read_file(d / "a.log");
  ASSERT_EQ(run(sadr + set + " -o " + (d / "full").string(), d / "b.log"), 0)
      << read_file(d / "b.log");
  ASSERT_EQ(run(sadr + set + " --stop-at 0.2 -o " + (d / "half").string(), d / "c.log"), 0)
      << read_file(d / "c.log");
  ASSERT_EQ(run(bin("sadr") + " resume -q " + (d / "half" / "checkpoint").string(), d / "d.log"), 0)
      << read_file(d / "d.log");
  expect_same_frames(d / "full", d / "half");
  // The override changed the result: twice the birth rate.
  const auto base = read_csv(frames(d / "base").back()).column("A");
  const auto full = read_csv(frames(d / "full").back()).column("A");
  double sum_base = 0, sum_full = 0;
  for (double v : base) sum_base += v;
  for (double v : full) sum_full += v;
  EXPECT_GT(sum_full, 1.4 * sum_base) << sum_base << " vs " << sum_full;
  const auto j = nlohmann::json::parse(read_file(d / "full" / "run.json"));
  EXPECT_EQ(j["overrides"],
            nlohmann::json::array({"reactions[birth].rate=800", "output.checkpoint_every=0.1"}));
  const auto plain = nlohmann::json::parse(read_file(d / "base" / "run.json"));
  EXPECT_NE(j["scene_hash"], plain["scene_hash"]);
  EXPECT_TRUE(plain["overrides"].empty());
  // A bad override is an input error naming it (exit 1).
  EXPECT_EQ(run(sadr + "--set reactions[birth].rate=-1 -o " + (d / "bad").string(), d / "e.log"),
            1);
  EXPECT_NE(read_file(d / "e.log").find("(set by --set reactions[birth].rate=-1)"),
            std::string::npos)
      << read_file(d / "e.log");
  if (!HasFailure()) fs::remove_all(d);
}

nlohmann::json manifest(const fs::path& dir) {
  return nlohmann::json::parse(read_file(dir / "sweep.json"));
}

/// A sweep file next to `scene`.
fs::path write_sweep(const fs::path& d, const std::string& body) {
  const fs::path p = d / "sweep.yaml";
  std::ofstream(p) << "scene: scene.yaml\n" << body;
  return p;
}

std::string sweep_cmd(const fs::path& sweep, const fs::path& out, const std::string& extra = "") {
  return bin("sadr") + " sweep " + sweep.string() + " -o " + out.string() + " " + extra;
}

TEST(SweepCli, DryRunChecksEveryPointListsTheRunsAndWritesNothing) {
  const fs::path d = scratch("sweep-dry");
  write_scene(d, birth_death_scene(16, 400.0, 1.0, 0.4, "[0.2, 0.4]", "[csv]"));
  const fs::path sweep = write_sweep(d,
                                     "realizations: 3\nseed: 3\n"
                                     "parameters:\n  grid:\n    reactions[birth].rate: [0, 400]\n");
  ASSERT_EQ(run(sweep_cmd(sweep, d / "a", "--dry-run"), d / "a.log"), 0) << read_file(d / "a.log");
  const std::string log = read_file(d / "a.log");
  EXPECT_NE(log.find("2 points x 3 realizations = 6 runs"), std::string::npos) << log;
  EXPECT_NE(log.find("point 1: reactions[birth].rate=400 -> runs/p0001_r0000 .. runs/p0001_r0002"),
            std::string::npos)
      << log;
  // point 0 sets the birth rate to 0: its scene is valid, with the warning it earns
  EXPECT_NE(log.find("rate 0: reaction 'birth' never fires"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(d / "a")) << "a dry run writes nothing";
  // A point whose scene is invalid fails the dry run, naming the point.
  const fs::path bad = write_sweep(d, "parameters:\n  grid:\n    reactions[birth].rate: [1, -1]\n");
  EXPECT_EQ(run(sweep_cmd(bad, d / "b", "--dry-run"), d / "b.log"), 1) << read_file(d / "b.log");
  EXPECT_NE(read_file(d / "b.log").find("point 1:"), std::string::npos) << read_file(d / "b.log");
  EXPECT_FALSE(fs::exists(d / "b"));
  if (!HasFailure()) fs::remove_all(d);
}

TEST(SweepCli, GridAggregatesEqualNumpyAndDoNotDependOnTheWorkers) {
  const fs::path d = scratch("sweep-grid");
  write_scene(d, birth_death_scene(16, 400.0, 1.0, 0.4, "[0.2, 0.4]", "[csv]"));
  const fs::path sweep = write_sweep(d,
                                     "realizations: 4\nseed: 3\nkeep: all\n"
                                     "parameters:\n  grid:\n    reactions[birth].rate: [200, 400]\n"
                                     "executor: {type: local, workers: 2}\n");
  ASSERT_EQ(run(sweep_cmd(sweep, d / "a"), d / "a.log"), 0) << read_file(d / "a.log");
  const auto m = manifest(d / "a");
  ASSERT_EQ(m["runs"].size(), 8u);
  std::set<std::uint64_t> seeds;
  for (const auto& r : m["runs"]) {
    EXPECT_EQ(r["state"], "ok") << r.dump();
    EXPECT_EQ(r["attempts"], 1);
    seeds.insert(r["seed"].get<std::uint64_t>());
  }
  EXPECT_EQ(seeds.size(), 8u) << "every run has its own seed";
  EXPECT_EQ(m["points"][1]["overrides"], nlohmann::json::array({"reactions[birth].rate=400"}));
  EXPECT_EQ(m["aggregates"]["1"]["state"], "done");
  // The run's manifest records the point's overrides and its seed.
  const auto rj = nlohmann::json::parse(read_file(d / "a" / "runs" / "p0001_r0002" / "run.json"));
  EXPECT_EQ(rj["overrides"][0], "reactions[birth].rate=400");
  EXPECT_EQ(rj["seed"], m["runs"][6]["seed"]);
  EXPECT_EQ(run("/usr/bin/python3 " + std::string(SADR_SOURCE_DIR) +
                    "/tests/e2e/sweep_stats_check.py " + (d / "a").string(),
                d / "numpy.log"),
            0)
      << read_file(d / "numpy.log");
  // One worker instead of two: the same seeds, the same aggregates, byte for byte.
  ASSERT_EQ(run(sweep_cmd(sweep, d / "b", "--workers 1"), d / "b.log"), 0)
      << read_file(d / "b.log");
  for (const char* f : {"points/p0000/frame_000002.csv", "points/p0001/frame_000001.vtu",
                        "points/p0001/aggregate.pvd", "observables.csv"}) {
    EXPECT_FALSE(read_file(d / "a" / f).empty()) << f;
    EXPECT_TRUE(read_file(d / "a" / f) == read_file(d / "b" / f)) << f;
  }
  // Tidy observables: one row per run, frame and species.
  const std::string obs = read_file(d / "a" / "observables.csv");
  EXPECT_EQ(obs.substr(0, obs.find('\n')),
            "point,realization,reactions[birth].rate,frame,time,species,total");
  EXPECT_EQ(std::count(obs.begin(), obs.end(), '\n'), 1 + 8 * 3);
  // The summary plot of the total against the swept rate (python3-matplotlib).
  ASSERT_EQ(run("/usr/bin/python3 " + std::string(SADR_SOURCE_DIR) +
                    "/orchestrator/app/sweep_plot.py " + (d / "a").string(),
                d / "plot.log"),
            0)
      << read_file(d / "plot.log");
  EXPECT_EQ(read_file(d / "a" / "summary.png").substr(1, 3), "PNG");
  EXPECT_NE(read_file(d / "plot.log").find("\n200.0,62.5,"), std::string::npos)
      << read_file(d / "plot.log");
  // Running it again runs nothing.
  ASSERT_EQ(run(sweep_cmd(sweep, d / "a"), d / "c.log"), 0) << read_file(d / "c.log");
  EXPECT_NE(read_file(d / "c.log").find("executed 0 runs, skipped 8 finished"), std::string::npos)
      << read_file(d / "c.log");
  if (!HasFailure()) fs::remove_all(d);
}

TEST(SweepCli, SceneNamedObservablesAreInTheTidyTableAndEqualTheFrames) {
  const fs::path d = scratch("sweep-observables");
  std::string scene = birth_death_scene(8, 400.0, 1.0, 0.4, "[0.2, 0.4]", "[csv]");
  scene = replace_once(scene, "particles:",
                       "regions:\n  - {name: left, shape: box, lower: [0.0], upper: [0.5]}\n"
                       "particles:");
  scene = replace_once(scene, "formats: [csv]}",
                       "formats: [csv], observables: [{name: A_left, species: A, region: left}, "
                       "{name: A_mean, species: A, stat: mean}]}");
  write_scene(d, scene);
  const fs::path sweep = write_sweep(d,
                                     "realizations: 2\nkeep: all\nparameters:\n  zip:\n"
                                     "    reactions[death].rate: [1, 2]\n");
  ASSERT_EQ(run(sweep_cmd(sweep, d / "s", "-q"), d / "a.log"), 0) << read_file(d / "a.log");
  // Every (run, frame) has its A row, then A_left and A_mean, equal to what the frame holds.
  std::istringstream obs(read_file(d / "s" / "observables.csv"));
  std::string line;
  std::getline(obs, line);
  ASSERT_EQ(line, "point,realization,reactions[death].rate,frame,time,species,total");
  std::map<std::string, double> got;  // "point,realization,frame,name" -> value
  int rows = 0;
  while (std::getline(obs, line)) {
    std::vector<std::string> c;
    std::istringstream r(line);
    for (std::string cell; std::getline(r, cell, ',');) c.push_back(cell);
    ASSERT_EQ(c.size(), 7u) << line;
    got[c[0] + "," + c[1] + "," + c[3] + "," + c[5]] = std::stod(c[6]);
    ++rows;
  }
  EXPECT_EQ(rows, 2 * 2 * 3 * 3) << "points x realizations x frames x (A, A_left, A_mean)";
  for (int p = 0; p < 2; ++p) {
    for (int r = 0; r < 2; ++r) {
      char dir[32];
      std::snprintf(dir, sizeof dir, "runs/p%04d_r%04d", p, r);
      const auto fr = frames(d / "s" / dir);
      ASSERT_EQ(fr.size(), 3u);
      for (std::size_t k = 0; k < fr.size(); ++k) {
        const CsvFrame f = read_csv(fr[k]);
        const auto a = f.column("A"), x = f.column("x");
        double left = 0, all = 0;
        for (std::size_t i = 0; i < a.size(); ++i) {
          all += a[i];
          if (x[i] <= 0.5) left += a[i];
        }
        const std::string key =
            std::to_string(p) + "," + std::to_string(r) + "," + std::to_string(k) + ",";
        EXPECT_EQ(got.at(key + "A"), all) << key;
        EXPECT_EQ(got.at(key + "A_left"), left) << key;
        EXPECT_DOUBLE_EQ(got.at(key + "A_mean"), all / static_cast<double>(a.size())) << key;
      }
    }
  }
  EXPECT_GT(got.at("0,0,2,A_left"), 0) << "the region holds molecules";
  // A bad observable is refused at the scene line, naming what is allowed.
  write_scene(d, replace_once(scene, "species: A, region: left", "species: B, region: left"));
  EXPECT_EQ(run(bin("sadr") + " validate " + (d / "scene.yaml").string(), d / "b.log"), 1);
  EXPECT_NE(read_file(d / "b.log").find("species 'B' is not written to the frames"),
            std::string::npos)
      << read_file(d / "b.log");
  write_scene(d, replace_once(scene, "name: A_left", "name: A"));
  EXPECT_EQ(run(bin("sadr") + " validate " + (d / "scene.yaml").string(), d / "c.log"), 1);
  EXPECT_NE(read_file(d / "c.log").find("'A' cannot name an observable"), std::string::npos)
      << read_file(d / "c.log");
  if (!HasFailure()) fs::remove_all(d);
}

TEST(SweepCli, AFailedRunIsReportedTheOthersFinishAndAReRunCompletesIt) {
  const fs::path d = scratch("sweep-fail");
  write_scene(d, birth_death_scene(8, 400.0, 1.0, 0.4, "[0.2, 0.4]", "[csv, vtu]"));
  const fs::path sweep = write_sweep(
      d, "realizations: 2\nretries: 1\nparameters:\n  zip:\n    reactions[death].rate: [1, 2]\n");
  // Bad input for one run: its run.json is a directory, so the run cannot write it.
  fs::create_directories(d / "s" / "runs" / "p0001_r0000" / "run.json");
  EXPECT_EQ(run(sweep_cmd(sweep, d / "s"), d / "a.log"), 3) << read_file(d / "a.log");
  const std::string log = read_file(d / "s" / "../a.log");
  EXPECT_NE(log.find("runs not finished"), std::string::npos) << log;
  auto m = manifest(d / "s");
  const auto& bad = m["runs"][2];
  EXPECT_EQ(bad["state"], "failed") << bad.dump();
  EXPECT_EQ(bad["exit_code"], 5) << bad.dump();  // I/O failure
  EXPECT_NE(bad["reason"].get<std::string>().find("run.json"), std::string::npos) << bad.dump();
  EXPECT_EQ(bad["attempts"], 2) << "retried once";
  for (int i : {0, 1, 3}) EXPECT_EQ(m["runs"][i]["state"], "ok") << m["runs"][i].dump();
  EXPECT_EQ(m["aggregates"]["0"]["state"], "done");
  EXPECT_EQ(m["aggregates"]["1"]["state"], "incomplete");
  // Fixed, the re-run executes only the failed run.
  fs::remove_all(d / "s" / "runs" / "p0001_r0000" / "run.json");
  ASSERT_EQ(run(sweep_cmd(sweep, d / "s"), d / "b.log"), 0) << read_file(d / "b.log");
  EXPECT_NE(read_file(d / "b.log").find("executed 1 runs, skipped 3 finished"), std::string::npos)
      << read_file(d / "b.log");
  m = manifest(d / "s");
  for (int i : {0, 1, 3}) EXPECT_EQ(m["runs"][i]["attempts"], 1) << "not recomputed";
  EXPECT_EQ(m["runs"][2]["attempts"], 3);
  EXPECT_EQ(m["aggregates"]["1"]["state"], "done");
  // keep: aggregates: realization 0 keeps its frames, realization 1 only its manifests.
  EXPECT_TRUE(fs::exists(d / "s" / "runs" / "p0001_r0000" / "frames"));
  EXPECT_FALSE(fs::exists(d / "s" / "runs" / "p0001_r0001" / "frames"));
  EXPECT_EQ(m["runs"][3]["kept"], "run.json, result.json, worker.log");
  EXPECT_EQ(m["runs"][2]["kept"], "all");
  if (!HasFailure()) fs::remove_all(d);
}

TEST(SweepCli, AKilledWorkerIsReportedAndTheReRunResumesItFromItsCheckpoint) {
  const fs::path d = scratch("sweep-kill");
  // About 6e6 events per run (~1 s here), a checkpoint every 0.25: the kill comes within
  // milliseconds of the first checkpoint, with 7/8 of the run still ahead.
  std::string scene = birth_death_scene(16, 3e6, 1.0, 2.0, "[1.0, 2.0]", "[csv]");
  scene =
      scene.replace(scene.find("formats: [csv]}"), 15, "formats: [csv], checkpoint_every: 0.25}");
  write_scene(d, scene);
  const fs::path sweep = write_sweep(
      d, "realizations: 2\nretries: 0\nkeep: all\nexecutor: {type: local, workers: 1}\n");
  const fs::path out = d / "s";
  std::thread killer([&] {
    const fs::path cp = out / "runs" / "p0000_r0000" / "checkpoint" / "checkpoint.json";
    for (int i = 0; i < 3000 && !fs::exists(cp); ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    // The worker's pid (the [s] keeps pgrep from matching its own shell), then SIGKILL.
    FILE* p = popen(("pgrep -f '[s]weep-task " + out.string() + " --index 0 '").c_str(), "r");
    int pid = 0;
    if (p != nullptr) {
      if (std::fscanf(p, "%d", &pid) != 1) pid = 0;
      pclose(p);
    }
    if (pid > 0) kill(pid, SIGKILL);
  });
  const int rc = run(sweep_cmd(sweep, out), d / "a.log");
  killer.join();
  auto m = manifest(out);
  ASSERT_NE(m["runs"][0]["state"], "ok") << "run 0 finished before the kill reached it";
  EXPECT_EQ(rc, 3) << read_file(d / "a.log");
  EXPECT_EQ(m["runs"][0]["state"], "failed");
  EXPECT_EQ(m["runs"][0]["exit_code"], 128 + 9);
  EXPECT_NE(m["runs"][0]["reason"].get<std::string>().find("killed by signal 9"), std::string::npos)
      << m["runs"][0].dump();
  EXPECT_EQ(m["runs"][1]["state"], "ok") << "the other run went on";
  ASSERT_EQ(run(sweep_cmd(sweep, out), d / "b.log"), 0) << read_file(d / "b.log");
  EXPECT_NE(read_file(d / "b.log").find("executed 1 runs, skipped 1 finished"), std::string::npos)
      << read_file(d / "b.log");
  const auto res = nlohmann::json::parse(read_file(out / "runs" / "p0000_r0000" / "result.json"));
  EXPECT_EQ(res["resumed"], true) << res.dump();
  m = manifest(out);
  EXPECT_EQ(m["runs"][1]["attempts"], 1);
  EXPECT_EQ(m["aggregates"]["0"]["state"], "done");
  if (!HasFailure()) fs::remove_all(d);
}

TEST(SweepCli, ConfidenceIntervalsCoverTheExactBirthDeathMean) {
  // 400 independent voxels, X(1) ~ Poisson(lambda), lambda = 10 (1 - e^-1),
  // R = 10 realizations: the t interval covers lambda with probability
  // p = 0.9475 (numpy, 2e6 Poisson samples, +-0.0002). Covered voxels ~
  // Binomial(400, p): mean 379, sd 4.46; accepted within 4 sd (false-failure
  // rate 6e-5). The grand mean of 4000 samples: sd sqrt(lambda / 4000) = 0.040.
  const fs::path d = scratch("sweep-coverage");
  write_scene(d, birth_death_scene(400, 4000.0, 1.0, 1.0, "[1.0]", "[csv]"));
  const fs::path sweep = write_sweep(d, "realizations: 10\nseed: 77\n");
  ASSERT_EQ(run(sweep_cmd(sweep, d / "s"), d / "a.log"), 0) << read_file(d / "a.log");
  const CsvFrame f = read_csv(d / "s" / "points" / "p0000" / "frame_000001.csv");
  const double lambda = 10.0 * (1.0 - std::exp(-1.0));
  ASSERT_EQ(f.rows(), 400u);
  int covered = 0;
  double grand = 0;
  for (std::size_t i = 0; i < f.rows(); ++i) {
    covered += f.column("A_ci95_lo")[i] <= lambda && lambda <= f.column("A_ci95_hi")[i];
    grand += f.column("A_mean")[i] / 400.0;
  }
  const double sd = std::sqrt(400 * 0.9475 * 0.0525);
  EXPECT_NEAR(covered, 400 * 0.9475, 4 * sd) << covered << " of 400 intervals cover " << lambda;
  EXPECT_NEAR(grand, lambda, 4 * std::sqrt(lambda / 4000.0));
  if (!HasFailure()) fs::remove_all(d);
}

TEST(SweepCli, AnInvalidPointIsRefusedBeforeAnythingRuns) {
  const fs::path d = scratch("sweep-invalid");
  write_scene(d, birth_death_scene(8, 400.0, 1.0, 0.4, "[0.4]", "[csv]"));
  const fs::path sweep =
      write_sweep(d,
                  "parameters:\n  points:\n    - {\"reactions[birth].rate\": 1}\n"
                  "    - reactions[birth].rate: -1\n");
  EXPECT_EQ(run(sweep_cmd(sweep, d / "s"), d / "a.log"), 1);
  const std::string log = read_file(d / "a.log");
  EXPECT_NE(log.find("point 1: "), std::string::npos) << log;
  EXPECT_NE(log.find("(set by --set reactions[birth].rate=-1)"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(d / "s" / "sweep.json"));
  const fs::path typo = d / "typo.yaml";
  std::ofstream(typo) << "scene: scene.yaml\nrealisations: 2\n";
  EXPECT_EQ(run(bin("sadr") + " sweep " + typo.string() + " -o " + (d / "t").string(), d / "b.log"),
            1);
  EXPECT_NE(read_file(d / "b.log").find("did you mean 'realizations'?"), std::string::npos)
      << read_file(d / "b.log");
  if (!HasFailure()) fs::remove_all(d);
}

TEST(SweepCli, RunsOfDifferentEffectiveScenesAreNotAggregatedTogether) {
  const fs::path d = scratch("sweep-hash");
  const fs::path scene =
      write_scene(d, birth_death_scene(8, 400.0, 1.0, 0.4, "[0.2, 0.4]", "[csv]"));
  const fs::path sweep = write_sweep(d, "realizations: 2\nretries: 0\n");
  fs::create_directories(d / "s" / "runs" / "p0000_r0001" / "run.json");  // run 1 fails
  EXPECT_EQ(run(sweep_cmd(sweep, d / "s"), d / "a.log"), 3) << read_file(d / "a.log");
  // The base scene is edited before the re-run: run 1 now runs another scene.
  fs::remove_all(d / "s" / "runs" / "p0000_r0001" / "run.json");
  std::ofstream(scene, std::ios::app) << "# edited\n";
  EXPECT_EQ(run(sweep_cmd(sweep, d / "s"), d / "b.log"), 1) << read_file(d / "b.log");
  EXPECT_NE(read_file(d / "b.log").find("point 0 not aggregated (refused)"), std::string::npos)
      << read_file(d / "b.log");
  const auto m = manifest(d / "s");
  EXPECT_NE(m["runs"][0]["scene_hash"], m["runs"][1]["scene_hash"]);
  EXPECT_EQ(m["aggregates"]["0"]["state"], "refused") << m["aggregates"].dump();
  EXPECT_NE(m["aggregates"]["0"]["notes"][0].get<std::string>().find("different effective scenes"),
            std::string::npos);
  EXPECT_FALSE(fs::exists(d / "s" / "points" / "p0000" / "frame_000001.csv"));
  if (!HasFailure()) fs::remove_all(d);
}

TEST(SweepCli, InterruptStopsTheWorkersAtACheckpointAndResumeGivesTheSameAggregates) {
  const fs::path d = scratch("sweep-interrupt");
  // As the kill test: the interrupt comes within milliseconds of the first checkpoint.
  std::string scene = birth_death_scene(16, 3e6, 1.0, 2.0, "[1.0, 2.0]", "[csv]");
  scene =
      scene.replace(scene.find("formats: [csv]}"), 15, "formats: [csv], checkpoint_every: 0.25}");
  write_scene(d, scene);
  const fs::path sweep = write_sweep(d, "realizations: 2\nexecutor: {type: local, workers: 2}\n");
  ASSERT_EQ(run(sweep_cmd(sweep, d / "ref", "-q"), d / "ref.log"), 0) << read_file(d / "ref.log");
  const fs::path out = d / "s";
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const int fd = open((d / "a.log").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 2);
    const std::string exe = bin("sadr");
    execl(exe.c_str(), exe.c_str(), "sweep", sweep.c_str(), "-o", out.c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  const fs::path cp = out / "runs" / "p0000_r0000" / "checkpoint" / "checkpoint.json";
  for (int i = 0; i < 3000 && !fs::exists(cp); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  kill(pid, SIGINT);  // as Ctrl-C: the sweep forwards SIGTERM to its workers
  int status = 0;
  waitpid(pid, &status, 0);
  auto m = manifest(out);
  ASSERT_FALSE(m["runs"][0]["state"] == "ok" && m["runs"][1]["state"] == "ok")
      << "both runs finished before the interrupt reached them";
  EXPECT_EQ(WEXITSTATUS(status), 130) << read_file(d / "a.log");
  EXPECT_NE(read_file(d / "a.log").find("interrupted"), std::string::npos)
      << read_file(d / "a.log");
  ASSERT_EQ(run(bin("sadr") + " sweep --resume " + out.string(), d / "b.log"), 0)
      << read_file(d / "b.log");
  for (const char* f : {"points/p0000/frame_000002.csv", "observables.csv"}) {
    EXPECT_TRUE(read_file(d / "ref" / f) == read_file(out / f)) << f;
  }
  if (!HasFailure()) fs::remove_all(d);
}

TEST(EnsembleCli, BadCellsNaNsAndMissingFramesAreRefusedNamingFileAndRow) {
  const fs::path d = scratch("ensemble-bad");
  const fs::path scene =
      write_scene(d, birth_death_scene(8, 400.0, 1.0, 0.4, "[0.2, 0.4]", "[csv]"));
  ASSERT_EQ(run(bin("sadr") + " run " + scene.string() + " -q -r 3 -o " + (d / "e").string(),
                d / "run.log"),
            0)
      << read_file(d / "run.log");
  const fs::path frame = d / "e" / "realization_0001" / "frames" / "frame_000001.csv";
  const std::string good = read_file(frame);
  const std::string ens = bin("sadr") + " ensemble " + (d / "e").string();
  const auto second_row_end = good.find('\n', good.find('\n') + 1);
  for (const char* value : {"abc", "nan"}) {
    std::string bad = good;
    const auto last_comma = bad.rfind(',', second_row_end);
    bad.replace(last_comma + 1, second_row_end - last_comma - 1, value);
    std::ofstream(frame) << bad;
    EXPECT_EQ(run(ens, d / "bad.log"), 1) << value;
    EXPECT_NE(read_file(d / "bad.log")
                  .find(frame.string() + ":2: column 'A': '" + value + "' is not a finite number"),
              std::string::npos)
        << read_file(d / "bad.log");
  }
  std::ofstream(frame) << good;
  fs::remove(d / "e" / "realization_0002" / "frames" / "frame_000002.csv");
  EXPECT_EQ(run(ens, d / "missing.log"), 1);
  EXPECT_NE(read_file(d / "missing.log").find("frame frame_000002.csv is missing"),
            std::string::npos)
      << read_file(d / "missing.log");
  // A realization of another effective scene (other --set values) is refused, naming both.
  fs::copy_file(d / "e" / "realization_0001" / "frames" / "frame_000002.csv",
                d / "e" / "realization_0002" / "frames" / "frame_000002.csv");
  ASSERT_EQ(run(bin("sadr") + " run " + scene.string() +
                    " -q --realization 3 --set reactions[birth].rate=800 -o " + (d / "e").string(),
                d / "other.log"),
            0)
      << read_file(d / "other.log");
  EXPECT_EQ(run(ens, d / "mixed.log"), 1);
  EXPECT_NE(read_file(d / "mixed.log").find("realization_0003 ran the effective scene"),
            std::string::npos)
      << read_file(d / "mixed.log");
  EXPECT_NE(read_file(d / "mixed.log").find("refusing to combine runs of different scenes"),
            std::string::npos)
      << read_file(d / "mixed.log");
  if (!HasFailure()) fs::remove_all(d);
}

TEST(EnsembleCli, AFailedRealizationDoesNotStopTheOthersAndResumeCompletesIt) {
  const fs::path d = scratch("ensemble-fault");
  const fs::path scene =
      write_scene(d, birth_death_scene(8, 400.0, 1.0, 0.4, "[0.2, 0.4]", "[csv]"));
  const std::string sadr = bin("sadr") + " ";
  ASSERT_EQ(
      run(sadr + "run " + scene.string() + " -q -r 3 -o " + (d / "ref").string(), d / "ref.log"), 0)
      << read_file(d / "ref.log");
  // Bad input for realization 1: its run.json is a directory.
  fs::create_directories(d / "e" / "realization_0001" / "run.json");
  EXPECT_EQ(run(sadr + "run " + scene.string() + " -q -r 3 -j 2 --force -o " + (d / "e").string(),
                d / "a.log"),
            3);
  const std::string log = read_file(d / "a.log");
  EXPECT_NE(log.find("realization 1 failed: "), std::string::npos) << log;
  EXPECT_NE(log.find("sadr resume " + (d / "e").string()), std::string::npos) << log;
  const auto j = nlohmann::json::parse(read_file(d / "e" / "ensemble.json"));
  ASSERT_EQ(j["failed"].size(), 1u) << j.dump();
  EXPECT_EQ(j["failed"][0]["realization"], 1);
  EXPECT_EQ(j["failed"][0]["exit_code"], 5);
  EXPECT_TRUE(fs::exists(d / "e" / "realization_0002" / "run.json")) << "the others went on";
  EXPECT_NE(read_file(d / "e" / "ensemble" / "frame_000002.csv").find(",2,"), std::string::npos)
      << "the ensemble says it used 2 realizations";
  fs::remove_all(d / "e" / "realization_0001" / "run.json");
  ASSERT_EQ(run(sadr + "resume " + (d / "e").string() + " -q", d / "b.log"), 0)
      << read_file(d / "b.log");
  EXPECT_NE(read_file(d / "b.log").find("resumed 1 of 3 realizations"), std::string::npos)
      << read_file(d / "b.log");
  for (const char* f : {"frame_000001.csv", "frame_000002.csv"}) {
    EXPECT_TRUE(read_file(d / "ref" / "ensemble" / f) == read_file(d / "e" / "ensemble" / f)) << f;
  }
  if (!HasFailure()) fs::remove_all(d);
}

/// A copy of sadr in DIR/bin whose ssa_service is a wrapper that fails to
/// start (exit 9) for realization 1 the first `failures` times, then execs
/// the real service: a transient fault of one realization (sadr starts the
/// services next to its own executable; the endpoint ends in "-<realization>").
std::string sadr_with_flaky_realization_1(const fs::path& d, int failures) {
  const fs::path b = d / "bin";
  fs::create_directories(b);
  fs::copy_file(bin("sadr"), b / "sadr", fs::copy_options::overwrite_existing);
  if (!fs::exists(b / "fluid_service"))
    fs::create_symlink(bin("fluid_service"), b / "fluid_service");
  std::ofstream w(b / "ssa_service");
  w << "#!/bin/sh\n"
       "for a in \"$@\"; do case \"$a\" in *-1)\n"
       "  n=$(cat '"
    << (d / "failures").string()
    << "' 2>/dev/null || echo 0)\n"
       "  if [ \"$n\" -lt "
    << failures << " ]; then echo $((n + 1)) > '" << (d / "failures").string()
    << "'; echo 'injected fault' >&2; exit 9; fi;;\n"
       "esac; done\n"
       "exec '"
    << bin("ssa_service") << "' \"$@\"\n";
  w.close();
  fs::permissions(b / "ssa_service", fs::perms::owner_all);
  return (b / "sadr").string() + " ";
}

TEST(EnsembleCli, AFailedRealizationIsRetriedUpToTheLimit) {
  const fs::path d = scratch("ensemble-retry");
  const fs::path scene =
      write_scene(d, birth_death_scene(8, 400.0, 1.0, 0.4, "[0.2, 0.4]", "[csv]"));
  ASSERT_EQ(run(bin("sadr") + " run " + scene.string() + " -q -r 3 -o " + (d / "ref").string(),
                d / "ref.log"),
            0)
      << read_file(d / "ref.log");
  // Realization 1 fails once: the default retry (--retries 1) completes the ensemble.
  const std::string sadr = sadr_with_flaky_realization_1(d, 1);
  ASSERT_EQ(
      run(sadr + "run " + scene.string() + " -q -r 3 -j 2 -o " + (d / "a").string(), d / "a.log"),
      0)
      << read_file(d / "a.log");
  EXPECT_NE(read_file(d / "a.log").find("realization 1, attempt 1 of 2 failed (exit 3)"),
            std::string::npos)
      << read_file(d / "a.log");
  EXPECT_EQ(read_file(d / "failures"), "1\n");
  for (const char* f : {"frame_000001.csv", "frame_000002.csv"}) {
    EXPECT_TRUE(read_file(d / "ref" / "ensemble" / f) == read_file(d / "a" / "ensemble" / f)) << f;
  }
  // It fails three times: --retries 1 stops after two attempts and says so.
  fs::remove(d / "failures");
  const std::string flaky = sadr_with_flaky_realization_1(d, 3);
  EXPECT_EQ(
      run(flaky + "run " + scene.string() + " -q -r 3 -j 2 --retries 1 -o " + (d / "b").string(),
          d / "b.log"),
      3)
      << read_file(d / "b.log");
  EXPECT_EQ(read_file(d / "failures"), "2\n") << "two attempts, no more";
  auto j = nlohmann::json::parse(read_file(d / "b" / "ensemble.json"));
  ASSERT_EQ(j["failed"].size(), 1u) << j.dump();
  EXPECT_EQ(j["failed"][0]["realization"], 1);
  EXPECT_EQ(j["failed"][0]["attempts"], 2);
  EXPECT_EQ(j["failed"][0]["exit_code"], 3);
  EXPECT_NE(j["failed"][0]["reason"].get<std::string>().find("ssa_service"), std::string::npos)
      << j.dump();
  EXPECT_EQ(j["retries"], 1);
  // `sadr resume DIR --retries 0` tries once more (the third failure), then the fourth start works.
  EXPECT_EQ(run(flaky + "resume " + (d / "b").string() + " -q --retries 0", d / "c.log"), 3)
      << read_file(d / "c.log");
  ASSERT_EQ(run(flaky + "resume " + (d / "b").string() + " -q --retries 0", d / "e.log"), 0)
      << read_file(d / "e.log");
  EXPECT_EQ(read_file(d / "failures"), "3\n");
  EXPECT_NE(read_file(d / "e.log").find("resumed 1 of 3 realizations"), std::string::npos)
      << read_file(d / "e.log");
  for (const char* f : {"frame_000001.csv", "frame_000002.csv"}) {
    EXPECT_TRUE(read_file(d / "ref" / "ensemble" / f) == read_file(d / "b" / "ensemble" / f)) << f;
  }
  if (!HasFailure()) fs::remove_all(d);
}

}  // namespace
}  // namespace sadr::orchestrator
