// SPDX-License-Identifier: MIT
// The `sadr` CLI end to end: real child processes (ipc), embedded threads
// (inproc) and remote services (tcp loopback) give byte-identical frames for
// the same seed; run to T == run to T/2 + resume; a killed ssa_service is
// detected, named, and the checkpoint survives; validate exit codes.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "cli_test_support.hpp"
#include "sadr/orchestrator/checkpoint.hpp"
#include "sadr/orchestrator/service_process.hpp"

namespace sadr::orchestrator {
namespace {
namespace fs = std::filesystem;
using namespace std::chrono_literals;
using namespace sadr::e2e;

/// 1D A + B -> 0 between Dirichlet walls (drawert2019 4.1, N = 17, N_b = 100),
/// short end time: a few hundred thousand events.
std::string annihilation_scene(double end, const std::string& outputs, double checkpoint_every) {
  std::ostringstream s;
  s << "name: ann\n"
       "dimension: 1\n"
       "box: {lower: [0.0], upper: [1.0], periodic: [false]}\n"
       "regions:\n"
       "  - {name: left_wall, shape: box, lower: [0.0], upper: [0.0]}\n"
       "  - {name: right_wall, shape: box, lower: [1.0], upper: [1.0]}\n"
       "particles:\n"
       "  spacing: 0.0625\n"
       "  density: 1.0\n"
       "  fill:\n"
       "    - {region: left_wall, kind: wall}\n"
       "    - {region: right_wall, kind: wall}\n"
       "    - {kind: fluid}\n"
       "fluid: {backend: static, h_over_dx: 1.8}\n"
       "species:\n"
       "  - name: A\n"
       "    diffusivity: 0.1\n"
       "    boundaries:\n"
       "      - {region: left_wall, condition: dirichlet, count: 100}\n"
       "      - {region: right_wall, condition: dirichlet, count: 0}\n"
       "  - name: B\n"
       "    diffusivity: 0.1\n"
       "    boundaries:\n"
       "      - {region: left_wall, condition: dirichlet, count: 0}\n"
       "      - {region: right_wall, condition: dirichlet, count: 100}\n"
       "reactions:\n"
       "  - {name: annihilation, equation: \"A + B -> 0\", rate: 0.1}\n"
       "time: {coupling_step: 0.01, end: "
    << end << "}\n"
    << "output:\n  times: " << outputs << "\n  formats: [csv, vtu]\n";
  if (checkpoint_every > 0) s << "  checkpoint_every: " << checkpoint_every << "\n";
  s << "seed: 42\n";
  return s.str();
}

TEST(OrchestratorCli, ProcessesEmbeddedAndRemoteGiveIdenticalFrames) {
  const fs::path d = scratch("modes");
  const fs::path scene = write_scene(d, annihilation_scene(0.3, "[0.1, 0.2, 0.3]", 0));
  const std::string sadr = bin("sadr") + " run " + scene.string() + " -q ";
  ASSERT_EQ(run(sadr + "-o " + (d / "proc").string(), d / "proc.log"), 0)
      << read_file(d / "proc.log");
  ASSERT_EQ(run(sadr + "--embedded -o " + (d / "emb").string(), d / "emb.log"), 0)
      << read_file(d / "emb.log");
  ASSERT_EQ(run_with_tcp_services(sadr, d / "tcp"), 0) << read_file(d / "tcp.log");
  expect_same_frames(d / "proc", d / "emb");
  expect_same_frames(d / "proc", d / "tcp");
  // The frames hold molecules (the run did something).
  const std::string last = read_file(d / "proc" / "frames" / "frame_000003.csv");
  EXPECT_EQ(last.rfind("time,id,kind,x,y,z,vx,vy,vz,density,mass,A,B\n", 0), 0u) << last;
  EXPECT_NE(last.find("\n0.3,1,0,0.0625,"), std::string::npos) << last;
  EXPECT_TRUE(fs::exists(d / "proc" / "ann.pvd"));
  EXPECT_TRUE(fs::exists(d / "proc" / "run.json"));
  if (!HasFailure()) fs::remove_all(d);  // keep the evidence of a failure
}

/// 2D periodic SDPD box with thermal noise (particles move every step) and one
/// stochastic tracer: the geometry goes to ssa_service every coupling step.
std::string moving_scene() {
  return "name: moving\n"
         "dimension: 2\n"
         "box: {lower: [0.0, 0.0], upper: [12.0, 12.0], periodic: [true, true]}\n"
         "particles: {spacing: 1.0, density: 1.0}\n"
         "fluid: {backend: sdpd, h_over_dx: 3.0, sound_speed: 10.0, shear_viscosity: 1.0, "
         "temperature: 0.01}\n"
         "species:\n"
         "  - {name: A, diffusivity: 2.0, initial: [{region: all, count: 3}]}\n"
         "time: {coupling_step: 0.05, end: 0.5}\n"
         "output: {times: [0.25, 0.5], formats: [csv]}\n"
         "seed: 7\n";
}

TEST(OrchestratorCli, SharedMemoryAndInlineGeometryGiveIdenticalFrames) {
  // Services launched here get the per-step geometry through a shared-memory
  // segment (sadr/wire/shared_geometry.hpp); --no-shared-memory and remote (tcp)
  // services get it inline. Same frames, and no segment is left in /dev/shm.
  const fs::path d = scratch("shm");
  const fs::path scene = write_scene(d, moving_scene());
  const std::string sadr = bin("sadr") + " run " + scene.string() + " --no-progress ";
  ASSERT_EQ(run(sadr + "-o " + (d / "shm").string(), d / "shm.log"), 0) << read_file(d / "shm.log");
  ASSERT_EQ(run(sadr + "--embedded -o " + (d / "emb").string(), d / "emb.log"), 0)
      << read_file(d / "emb.log");
  ASSERT_EQ(run(sadr + "--no-shared-memory -o " + (d / "inline").string(), d / "inline.log"), 0)
      << read_file(d / "inline.log");
  ASSERT_EQ(run_with_tcp_services(sadr, d / "tcp"), 0) << read_file(d / "tcp.log");
  for (const char* mode : {"shm", "emb"}) {
    const std::string log = read_file(d / (std::string(mode) + ".log"));
    const auto at = log.find("through shared memory /sadr-geometry-");
    ASSERT_NE(at, std::string::npos) << mode << ": " << log;
    const std::string name = log.substr(at + 22, log.find('\n', at) - at - 22);
    EXPECT_FALSE(fs::exists("/dev/shm" + name)) << name << " left behind";
  }
  for (const char* mode : {"inline", "tcp"}) {
    EXPECT_EQ(read_file(d / (std::string(mode) + ".log")).find("through shared memory"),
              std::string::npos)
        << mode;
  }
  expect_same_frames(d / "shm", d / "inline");
  expect_same_frames(d / "shm", d / "emb");
  expect_same_frames(d / "shm", d / "tcp");
  // The particles moved and the tracer is there (the comparison is not vacuous).
  const std::string last = read_file(d / "shm" / "frames" / "frame_000002.csv");
  EXPECT_EQ(last.rfind("time,id,kind,x,y,z,vx,vy,vz,density,mass,A\n", 0), 0u) << last;
  EXPECT_EQ(last.find(",0.5,0.5,0,"), std::string::npos) << "particle 0 did not move";
  if (!HasFailure()) fs::remove_all(d);  // keep the evidence of a failure
}

TEST(OrchestratorCli, OpenMpWaitsArePassiveUnlessTheUserChose) {
  // sadr re-executes itself with OMP_WAIT_POLICY=passive when neither it nor
  // GOMP_SPINCOUNT is set (common/openmp_env.hpp); the run manifest records what
  // the run saw, and a user's choice of either variable is left alone.
  const fs::path d = scratch("omp");
  const fs::path scene = write_scene(d, annihilation_scene(0.02, "[0.02]", 0));
  const std::string run_cmd = bin("sadr") + " run " + scene.string() + " -q --embedded -o ";
  ASSERT_EQ(
      run("env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT " + run_cmd + (d / "a").string(), d / "a.log"),
      0)
      << read_file(d / "a.log");
  const std::string a = read_file(d / "a" / "run.json");
  EXPECT_NE(a.find("\"OMP_WAIT_POLICY\": \"passive\""), std::string::npos) << a;
  EXPECT_NE(a.find("\"GOMP_SPINCOUNT\": \"\""), std::string::npos) << a;
  ASSERT_EQ(run("env -u GOMP_SPINCOUNT OMP_WAIT_POLICY=active " + run_cmd + (d / "b").string(),
                d / "b.log"),
            0)
      << read_file(d / "b.log");
  const std::string b = read_file(d / "b" / "run.json");
  EXPECT_NE(b.find("\"OMP_WAIT_POLICY\": \"active\""), std::string::npos) << b;
  EXPECT_NE(b.find("\"GOMP_SPINCOUNT\": \"\""), std::string::npos) << b;
  ASSERT_EQ(
      run("env -u OMP_WAIT_POLICY GOMP_SPINCOUNT=0 " + run_cmd + (d / "c").string(), d / "c.log"),
      0)
      << read_file(d / "c.log");
  const std::string c = read_file(d / "c" / "run.json");
  EXPECT_NE(c.find("\"OMP_WAIT_POLICY\": \"\""), std::string::npos) << c;
  EXPECT_NE(c.find("\"GOMP_SPINCOUNT\": \"0\""), std::string::npos) << c;
  if (!HasFailure()) fs::remove_all(d);  // keep the evidence of a failure
}

// `sadr run` of `scene` to its end into d/full and to t = 0.2 into d/half (the resume tests).
void run_full_and_half(const std::string& sadr, const fs::path& scene, const fs::path& d) {
  ASSERT_EQ(run(sadr + "run " + scene.string() + " -q -o " + (d / "full").string(), d / "a.log"), 0)
      << read_file(d / "a.log");
  ASSERT_EQ(run(sadr + "run " + scene.string() + " -q --stop-at 0.2 -o " + (d / "half").string(),
                d / "b.log"),
            0)
      << read_file(d / "b.log");
}

TEST(OrchestratorCli, RunHalfThenResumeEqualsFullRun) {
  const fs::path d = scratch("resume");
  const fs::path scene = write_scene(d, annihilation_scene(0.4, "[0.1, 0.2, 0.3, 0.4]", 0.1));
  const std::string sadr = bin("sadr") + " ";
  run_full_and_half(sadr, scene, d);
  if (HasFatalFailure()) return;
  EXPECT_EQ(frames(d / "half").size(), 2u * 3u);  // t = 0.1, 0.2 as csv + vtu (+ none at 0)
  ASSERT_EQ(run(sadr + "resume " + (d / "half" / "checkpoint").string() + " -q", d / "c.log"), 0)
      << read_file(d / "c.log");
  expect_same_frames(d / "full", d / "half");
  if (!HasFailure()) fs::remove_all(d);  // keep the evidence of a failure
}

// `sadr resume RUN_DIR` (the run's folder, as `sadr run -o` names it) finds
// RUN_DIR/checkpoint/checkpoint.json; a folder with no checkpoint is refused, naming the
// paths it looked for.
TEST(OrchestratorCli, ResumeOfARunFolderUsesItsCheckpointDirectory) {
  const fs::path d = scratch("resume_run_dir");
  const fs::path scene = write_scene(d, annihilation_scene(0.4, "[0.2, 0.4]", 0.1));
  const std::string sadr = bin("sadr") + " ";
  run_full_and_half(sadr, scene, d);
  if (HasFatalFailure()) return;
  ASSERT_EQ(run(sadr + "resume " + (d / "half").string() + " -q", d / "c.log"), 0)
      << read_file(d / "c.log");
  expect_same_frames(d / "full", d / "half");
  fs::create_directories(d / "none");
  EXPECT_EQ(run(sadr + "resume " + (d / "none").string() + " -q", d / "e.log"), 1);
  const std::string e = read_file(d / "e.log");
  EXPECT_NE(e.find((d / "none" / "checkpoint" / "checkpoint.json").string()), std::string::npos)
      << e;
  if (!HasFailure()) fs::remove_all(d);  // keep the evidence of a failure
}

TEST(OrchestratorCli, TwoRunsOfOneSceneWriteByteIdenticalCheckpoints) {
  const fs::path d = scratch("ckpt_bytes");
  std::string text = moving_scene();  // both services, each blob with a metadata map
  text.replace(text.find("formats: [csv]}"), 15, "formats: [csv], checkpoint_every: 0.25}");
  const fs::path scene = write_scene(d, text);
  const std::string sadr = bin("sadr") + " ";
  for (const char* out : {"a", "b"}) {
    ASSERT_EQ(run(sadr + "run " + scene.string() + " -q -o " + (d / out).string(), d / "log"), 0)
        << read_file(d / "log");
  }
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(d / "a" / "checkpoint")) {
    if (e.path().filename() != "checkpoint.json") names.push_back(e.path().filename().string());
  }
  ASSERT_EQ(names.size(), 2u);  // fluid and ssa blobs (names carry the content hash)
  for (const auto& name : names) {
    ASSERT_TRUE(fs::exists(d / "b" / "checkpoint" / name)) << name;
    EXPECT_EQ(read_file(d / "a" / "checkpoint" / name), read_file(d / "b" / "checkpoint" / name))
        << name;
  }
  if (!HasFailure()) fs::remove_all(d);  // keep the evidence of a failure
}

TEST(OrchestratorCli, KilledSsaServiceIsNamedAndTheCheckpointSurvives) {
  const fs::path d = scratch("kill");
  // Long enough that we can kill it mid-run; checkpoints every 0.05.
  const fs::path scene = write_scene(d, annihilation_scene(1000.0, "[1000.0]", 0.05));
  const fs::path out = d / "out";
  const pid_t pid = fork();
  if (pid == 0) {
    const std::string log = (d / "run.log").string();
    freopen(log.c_str(), "w", stderr);
    execl(bin("sadr").c_str(), "sadr", "run", scene.c_str(), "-q", "-o", out.c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  const fs::path cp = out / "checkpoint" / "checkpoint.json";
  for (int i = 0; i < 600 && !fs::exists(cp); ++i) std::this_thread::sleep_for(50ms);
  ASSERT_TRUE(fs::exists(cp)) << "no checkpoint within 30 s";
  // Find the ssa_service child and kill it hard.
  const std::string find =
      "pgrep -P " + std::to_string(pid) + " -x ssa_service > '" + (d / "pid").string() + "'";
  ASSERT_EQ(std::system(find.c_str()), 0);
  const pid_t child = std::stoi(read_file(d / "pid"));
  kill(child, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 3) << read_file(d / "run.log");
  const std::string log = read_file(d / "run.log");
  EXPECT_NE(log.find("ssa_service"), std::string::npos) << log;
  EXPECT_NE(log.find("killed by signal 9"), std::string::npos) << log;
  // The last good checkpoint is intact and loadable.
  const LoadedCheckpoint loaded = load_checkpoint(cp, "");
  EXPECT_GT(loaded.manifest.step_index, 0u);
  EXPECT_EQ(loaded.blobs.count("ssa"), 1u);
  if (!HasFailure()) fs::remove_all(d);  // keep the evidence of a failure
}

TEST(OrchestratorCli, RestartOnFailureRecoversFromTheCheckpointBitIdentically) {
  const fs::path d = scratch("restart");
  // About 1 s of wall time (long enough to be killed mid-run); checkpoints every 0.5 s.
  const fs::path scene = write_scene(d, annihilation_scene(20.0, "[5.0, 10.0, 15.0, 20.0]", 0.5));
  ASSERT_EQ(
      run(bin("sadr") + " run " + scene.string() + " -q -o " + (d / "ref").string(), d / "ref.log"),
      0)
      << read_file(d / "ref.log");
  const fs::path out = d / "out";
  const pid_t pid = fork();
  if (pid == 0) {
    const std::string log = (d / "run.log").string();
    freopen(log.c_str(), "w", stderr);
    execl(bin("sadr").c_str(), "sadr", "run", scene.c_str(), "-q", "--restart-on-failure", "2",
          "-o", out.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  const fs::path cp = out / "checkpoint" / "checkpoint.json";
  for (int i = 0; i < 600 && !fs::exists(cp); ++i) std::this_thread::sleep_for(10ms);
  const std::string find =
      "pgrep -P " + std::to_string(pid) + " -x ssa_service > '" + (d / "pid").string() + "'";
  if (std::system(find.c_str()) == 0) kill(std::stoi(read_file(d / "pid")), SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << read_file(d / "run.log");
  const std::string log = read_file(d / "run.log");
  EXPECT_NE(log.find("restarting the services (1 of 2)"), std::string::npos) << log;
  expect_same_frames(d / "ref", out);
  if (!HasFailure()) fs::remove_all(d);
}

TEST(OrchestratorCli, ArrayTasksPlusEnsembleEqualALocalEnsemble) {
  const fs::path d = scratch("array");
  const fs::path scene = write_scene(d, annihilation_scene(0.2, "[0.1, 0.2]", 0));
  ASSERT_EQ(
      run(bin("sadr") + " run " + scene.string() + " -q -r 4 -j 2 -o " + (d / "local").string(),
          d / "local.log"),
      0)
      << read_file(d / "local.log");
  // As a Slurm array would run them: one process per realization, any order.
  for (const char* k : {"2", "0", "3"}) {
    ASSERT_EQ(run(bin("sadr") + " run " + scene.string() + " -q --realization " + k + " -o " +
                      (d / "array").string(),
                  d / "task.log"),
              0)
        << read_file(d / "task.log");
  }
  ASSERT_EQ(run("SLURM_ARRAY_TASK_ID=1 " + bin("sadr") + " run " + scene.string() +
                    " -q --realization env -o " + (d / "array").string(),
                d / "task.log"),
            0)
      << read_file(d / "task.log");
  ASSERT_EQ(run(bin("sadr") + " ensemble " + (d / "array").string(), d / "ens.log"), 0)
      << read_file(d / "ens.log");
  for (const char* f : {"frame_000000.csv", "frame_000001.csv"}) {
    const std::string a = read_file(d / "local" / "ensemble" / f);
    EXPECT_FALSE(a.empty()) << f;
    EXPECT_TRUE(a == read_file(d / "array" / "ensemble" / f)) << f;
    EXPECT_NE(a.find(",4,"), std::string::npos) << "4 realizations per row: " << a.substr(0, 200);
  }
  EXPECT_EQ(run("env -u SLURM_ARRAY_TASK_ID -u JOB_COMPLETION_INDEX " + bin("sadr") + " run " +
                    scene.string() + " --realization env -o " + (d / "x").string(),
                d / "noenv.log"),
            1);
  EXPECT_NE(read_file(d / "noenv.log").find("SLURM_ARRAY_TASK_ID"), std::string::npos);
  if (!HasFailure()) fs::remove_all(d);
}

TEST(OrchestratorCli, ValidateExitCodes) {
  const fs::path d = scratch("validate");
  const fs::path good = write_scene(d, annihilation_scene(0.1, "[0.1]", 0));
  EXPECT_EQ(run(bin("sadr") + " validate " + good.string(), d / "good.log"), 0)
      << read_file(d / "good.log");
  std::string bad_text = annihilation_scene(0.1, "[0.1]", 0);
  bad_text.replace(bad_text.find("diffusivity: 0.1"), 16, "diffusivty: 0.1");
  const fs::path bad = d / "bad.yaml";
  std::ofstream(bad) << bad_text;
  EXPECT_EQ(run(bin("sadr") + " validate " + bad.string(), d / "bad.log"), 1);
  const std::string log = read_file(d / "bad.log");
  EXPECT_NE(log.find("bad.yaml:"), std::string::npos) << log;
  EXPECT_NE(log.find("did you mean 'diffusivity'"), std::string::npos) << log;
  EXPECT_EQ(run(bin("sadr") + " frobnicate", d / "usage.log"), 2);
  if (!HasFailure()) fs::remove_all(d);  // keep the evidence of a failure
}

}  // namespace
}  // namespace sadr::orchestrator
