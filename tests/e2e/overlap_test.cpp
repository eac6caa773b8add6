// SPDX-License-Identifier: MIT
// The overlapped coupling loop (SSA step k on a worker thread while the fluid
// computes step k + 1; --overlap / --no-overlap) end to end: byte-identical
// frames and checkpoints to the sequential loop in the three service modes, with
// a checkpoint interval that is not a multiple of the output times; --stop-at +
// resume; a killed ssa_service during an overlapped run is named and the
// checkpoint survives; the plan says whether overlap is on and why.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "cli_test_support.hpp"
#include "sadr/common/v1/snapshot.pb.h"
#include "sadr/orchestrator/checkpoint.hpp"
#include "sadr/orchestrator/service_process.hpp"

namespace sadr::orchestrator {
namespace {
namespace fs = std::filesystem;
using namespace std::chrono_literals;
using namespace sadr::e2e;

/// 2D periodic SDPD box with thermal noise (the particles move, so the geometry
/// goes to ssa_service and its graph is rebuilt every step) and a stochastic
/// tracer that reacts (A -> 0), Lie splitting: overlap is allowed. Outputs at
/// 0.3, 0.65, 1.0 with checkpoints every 0.4 (not a multiple of them).
std::string moving_scene(double end = 1.0) {
  return "name: ovl\n"
         "dimension: 2\n"
         "box: {lower: [0.0, 0.0], upper: [16.0, 16.0], periodic: [true, true]}\n"
         "particles: {spacing: 1.0, density: 1.0}\n"
         "fluid: {backend: sdpd, h_over_dx: 3.0, sound_speed: 10.0, shear_viscosity: 1.0, "
         "temperature: 0.01}\n"
         "species:\n"
         "  - {name: A, diffusivity: 2.0, initial: [{region: all, count: 5}]}\n"
         "reactions:\n"
         "  - {name: decay, equation: \"A -> 0\", rate: 0.3}\n"
         "time: {coupling_step: 0.05, end: " +
         std::to_string(end) +
         "}\n"
         "output:\n"
         "  times: [0.3, 0.65, " +
         std::to_string(end) +
         "]\n"
         "  formats: [csv]\n"
         "  checkpoint_every: 0.4\n"
         "seed: 11\n";
}

nlohmann::json run_json(const fs::path& out) {
  return nlohmann::json::parse(read_file(out / "run.json"));
}

/// Two checkpoints hold the same state: same step and time, and each service's
/// state blob byte-identical. (The Snapshot envelopes themselves are not compared
/// bytewise: protobuf serialises their metadata map in an unspecified order.)
void expect_same_checkpoint(const fs::path& a, const fs::path& b) {
  const LoadedCheckpoint ca = load_checkpoint(a / "checkpoint.json", "");
  const LoadedCheckpoint cb = load_checkpoint(b / "checkpoint.json", "");
  EXPECT_EQ(ca.manifest.step_index, cb.manifest.step_index);
  EXPECT_EQ(ca.manifest.time, cb.manifest.time);
  ASSERT_EQ(ca.blobs.size(), 2u) << a;
  ASSERT_EQ(cb.blobs.size(), 2u) << b;
  for (const auto& [service, blob] : ca.blobs) {
    ASSERT_EQ(cb.blobs.count(service), 1u) << service;
    common::v1::Snapshot sa, sb;
    ASSERT_TRUE(sa.ParseFromString(blob.bytes)) << service;
    ASSERT_TRUE(sb.ParseFromString(cb.blobs.at(service).bytes)) << service;
    EXPECT_FALSE(sa.blob().empty()) << service;
    EXPECT_TRUE(sa.blob() == sb.blob()) << service << " state differs: " << a << " vs " << b;
    EXPECT_EQ(sa.step_index(), sb.step_index()) << service;
    EXPECT_EQ(sa.time(), sb.time()) << service;
  }
}

TEST(Overlap, OverlappedAndSequentialLoopsGiveIdenticalFramesAndCheckpointsInAllModes) {
  const fs::path d = scratch("overlap-modes");
  const fs::path scene = write_scene(d, moving_scene());
  const std::string sadr = bin("sadr") + " run " + scene.string() + " -q ";
  for (const std::string mode : {"proc", "emb", "tcp"}) {
    for (const std::string loop : {"seq", "ovl"}) {
      const std::string flags = std::string(loop == "ovl" ? "--overlap " : "--no-overlap ") +
                                (mode == "emb" ? "--embedded " : "");
      const fs::path out = d / (mode + "-" + loop);
      const fs::path log = out.string() + ".log";
      if (mode == "tcp") {
        ASSERT_EQ(run_with_tcp_services(sadr + flags, out), 0) << read_file(log);
      } else {
        ASSERT_EQ(run(sadr + flags + "-o " + out.string(), log), 0) << read_file(log);
      }
      const auto j = run_json(out);
      EXPECT_EQ(j["plan"]["overlap"].get<bool>(), loop == "ovl") << mode << " " << loop;
      EXPECT_EQ(j["plan"]["overlap_reason"].get<std::string>(),
                loop == "ovl" ? "--overlap" : "--no-overlap");
      EXPECT_EQ(j["steps"].get<int>(), 20);
      // 20 steps; those ending at an output time (0.3, 0.65, 1.0 = the end) or a
      // checkpoint time (0.4, 0.8) run alone: 20 - 3 - 2 = 15 overlapped.
      EXPECT_EQ(j["overlapped_steps"].get<int>(), loop == "ovl" ? 15 : 0) << mode;
      // Every step is 0.05 long (all output and checkpoint times are multiples of it),
      // which the SDPD acoustic limit (just under 0.0375 here) splits into 2 sub-steps.
      EXPECT_EQ(j["fluid_substeps"].get<int>(), 40) << mode << " " << loop;
      const auto& t = j["timings_s"];
      for (const char* key : {"fluid", "fluid_compute", "ssa", "ssa_graph", "ssa_nsm", "transfer",
                              "coupling_loop", "ssa_wait"}) {
        EXPECT_TRUE(t.contains(key)) << key << " missing in " << mode << " " << loop;
      }
      EXPECT_GT(t["coupling_loop"].get<double>(), 0.0);
      EXPECT_EQ(frames(out).size(), 4u);  // t = 0 and the three output times
    }
    expect_same_frames(d / (mode + "-seq"), d / (mode + "-ovl"));
    expect_same_checkpoint(d / (mode + "-seq") / "checkpoint", d / (mode + "-ovl") / "checkpoint");
  }
  expect_same_frames(d / "proc-ovl", d / "emb-ovl");
  expect_same_frames(d / "proc-ovl", d / "tcp-ovl");
  // Not vacuous: molecules decayed and the particles moved.
  const CsvFrame last = read_csv(d / "proc-ovl" / "frames" / "frame_000003.csv");
  double molecules = 0;
  for (double a : last.column("A")) molecules += a;
  EXPECT_GT(molecules, 0.0);
  EXPECT_LT(molecules, 5.0 * 256);
  EXPECT_NE(last.column("x")[0], 0.5) << "particle 0 did not move";
  if (!HasFailure()) fs::remove_all(d);  // keep the evidence of a failure
}

TEST(Overlap, StopAtAndResumeAreBitIdenticalToAnUninterruptedRun) {
  const fs::path d = scratch("overlap-resume");
  const fs::path scene = write_scene(d, moving_scene());
  const std::string sadr = bin("sadr") + " ";
  const std::string run_scene = sadr + "run " + scene.string() + " -q ";
  ASSERT_EQ(run(run_scene + "--no-overlap -o " + (d / "full").string(), d / "full.log"), 0)
      << read_file(d / "full.log");
  // Stop at 0.45: not an output, not a checkpoint time; the overlapped run must
  // drain the SSA before its checkpoint, which then equals the sequential one.
  for (const std::string loop : {"seq", "ovl"}) {
    const std::string flag = loop == "ovl" ? "--overlap " : "--no-overlap ";
    ASSERT_EQ(
        run(run_scene + flag + "--stop-at 0.45 -o " + (d / loop).string(), d / (loop + ".log")), 0)
        << read_file(d / (loop + ".log"));
    const auto j = run_json(d / loop);
    EXPECT_EQ(j["status"].get<std::string>(), "interrupted");
    EXPECT_EQ(j["steps"].get<int>(), 9);
  }
  expect_same_checkpoint(d / "seq" / "checkpoint", d / "ovl" / "checkpoint");
  ASSERT_EQ(run(sadr + "resume " + (d / "ovl" / "checkpoint").string() + " -q --overlap",
                d / "resume.log"),
            0)
      << read_file(d / "resume.log");
  EXPECT_GT(run_json(d / "ovl")["overlapped_steps"].get<int>(), 0);
  expect_same_frames(d / "full", d / "ovl");
  expect_same_checkpoint(d / "full" / "checkpoint", d / "ovl" / "checkpoint");
  if (!HasFailure()) fs::remove_all(d);
}

TEST(Overlap, KilledSsaServiceDuringAnOverlappedRunIsNamedAndTheCheckpointSurvives) {
  const fs::path d = scratch("overlap-kill");
  const fs::path scene = write_scene(d, moving_scene(2000.0));  // minutes: killed long before
  const fs::path out = d / "out";
  const pid_t pid = fork();
  if (pid == 0) {
    const std::string log = (d / "run.log").string();
    freopen(log.c_str(), "w", stderr);
    execl(bin("sadr").c_str(), "sadr", "run", scene.c_str(), "-q", "--overlap", "-o", out.c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  const fs::path cp = out / "checkpoint" / "checkpoint.json";
  for (int i = 0; i < 600 && !fs::exists(cp); ++i) std::this_thread::sleep_for(50ms);
  ASSERT_TRUE(fs::exists(cp)) << "no checkpoint within 30 s";
  std::this_thread::sleep_for(200ms);  // well inside the overlapped steps between checkpoints
  const std::string find =
      "pgrep -P " + std::to_string(pid) + " -x ssa_service > '" + (d / "pid").string() + "'";
  ASSERT_EQ(std::system(find.c_str()), 0);
  kill(std::stoi(read_file(d / "pid")), SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status)) << "sadr did not exit normally (std::terminate?)";
  EXPECT_EQ(WEXITSTATUS(status), 3) << read_file(d / "run.log");
  const std::string log = read_file(d / "run.log");
  EXPECT_NE(log.find("ssa_service"), std::string::npos) << log;
  EXPECT_NE(log.find("killed by signal 9"), std::string::npos) << log;
  EXPECT_EQ(log.find("terminate"), std::string::npos) << log;
  const auto j = run_json(out);
  EXPECT_EQ(j["status"].get<std::string>().rfind("failed: ", 0), 0u) << j.dump();
  EXPECT_GT(j["overlapped_steps"].get<int>(), 0);
  const LoadedCheckpoint loaded = load_checkpoint(cp, "");
  EXPECT_GT(loaded.manifest.step_index, 0u);
  EXPECT_EQ(loaded.blobs.count("ssa"), 1u);
  EXPECT_EQ(loaded.blobs.count("fluid"), 1u);
  if (!HasFailure()) fs::remove_all(d);
}

TEST(Overlap, RestartOnFailureDuringAnOverlappedRunRecoversBitIdentically) {
  const fs::path d = scratch("overlap-restart");
  const fs::path scene = write_scene(d, moving_scene(12.0));  // about a second of wall time
  ASSERT_EQ(
      run(bin("sadr") + " run " + scene.string() + " -q --no-overlap -o " + (d / "ref").string(),
          d / "ref.log"),
      0)
      << read_file(d / "ref.log");
  const fs::path out = d / "out";
  const pid_t pid = fork();
  if (pid == 0) {
    const std::string log = (d / "run.log").string();
    freopen(log.c_str(), "w", stderr);
    execl(bin("sadr").c_str(), "sadr", "run", scene.c_str(), "-q", "--overlap",
          "--restart-on-failure", "2", "-o", out.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  const fs::path cp = out / "checkpoint" / "checkpoint.json";
  for (int i = 0; i < 600 && !fs::exists(cp); ++i) std::this_thread::sleep_for(10ms);
  const std::string find =
      "pgrep -P " + std::to_string(pid) + " -x ssa_service > '" + (d / "pid").string() + "'";
  const bool killed = std::system(find.c_str()) == 0;
  if (killed) kill(std::stoi(read_file(d / "pid")), SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << read_file(d / "run.log");
  if (killed) {
    EXPECT_NE(read_file(d / "run.log").find("restarting the services (1 of 2)"), std::string::npos)
        << read_file(d / "run.log");
  }
  EXPECT_GT(run_json(out)["overlapped_steps"].get<int>(), 0);
  expect_same_frames(d / "ref", out);
  if (!HasFailure()) fs::remove_all(d);
}

TEST(Overlap, ThePlanSaysWhetherOverlapIsOnAndWhy) {
  const fs::path d = scratch("overlap-plan");
  const fs::path scene = write_scene(d, moving_scene());
  const std::string sadr = bin("sadr") + " run " + scene.string() + " --no-progress --embedded ";
  struct Case {
    std::string flags, expect;
  };
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  const std::vector<Case> cases = {
      {"--no-overlap", "overlap ssa step k || fluid step k+1: off (--no-overlap)"},
      {"--overlap", "overlap ssa step k || fluid step k+1: on (--overlap)"},
      // Auto: on with a second hardware thread, even when the fluid uses them all.
      {"--fluid-threads " + std::to_string(hw),
       hw >= 2 ? "on (auto: a second hardware thread" : "off (auto: no second"},
      {"--fluid-threads 1 --ssa-threads 1",
       hw >= 2 ? "on (auto: a second hardware thread" : "off (auto: no second"},
      // Two realizations at once on the 2-core machine: one hardware thread each.
      {"-r " + std::to_string(hw) + " -j " + std::to_string(hw),
       "off (auto: no second hardware thread for the SSA"},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const fs::path out = d / std::string("o").append(std::to_string(i));
    const fs::path log = out.string() + ".log";
    ASSERT_EQ(run(sadr + cases[i].flags + " -o " + out.string(), log), 0) << read_file(log);
    EXPECT_NE(read_file(log).find(cases[i].expect), std::string::npos)
        << cases[i].flags << ": " << read_file(log);
  }
  EXPECT_EQ(run(sadr + "--overlap --no-overlap -o " + (d / "x").string(), d / "x.log"), 2)
      << read_file(d / "x.log");
  // Strang splitting: the fluid's second half step needs the SSA's result.
  const fs::path strang = write_scene(d,
                                      replace_once(moving_scene(), "coupling_step: 0.05,",
                                                   "coupling_step: 0.05, splitting: strang,"),
                                      "strang.yaml");
  ASSERT_EQ(run(bin("sadr") + " run " + strang.string() +
                    " --no-progress --embedded --overlap -o " + (d / "s").string(),
                d / "s.log"),
            0)
      << read_file(d / "s.log");
  EXPECT_NE(read_file(d / "s.log").find("off (strang splitting"), std::string::npos)
      << read_file(d / "s.log");
  EXPECT_EQ(run_json(d / "s")["overlapped_steps"].get<int>(), 0);
  if (!HasFailure()) fs::remove_all(d);
}

}  // namespace
}  // namespace sadr::orchestrator
