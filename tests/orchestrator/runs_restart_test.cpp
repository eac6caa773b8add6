// SPDX-License-Identifier: MIT
// sadr::orchestrator_campaign: exit codes, the restart policy (--restart-on-failure:
// service failures only, from the last checkpoint) and the retry policy
// (--retries of ensemble realizations).
#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "sadr/common/status.hpp"
#include "sadr/orchestrator/atomic_file.hpp"
#include "sadr/orchestrator/exit_codes.hpp"
#include "sadr/orchestrator/restart_policy.hpp"

namespace sadr::orchestrator {
namespace {
namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path d =
      fs::temp_directory_path() / ("sadr-restart-" + std::to_string(getpid()) + "-" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

/// A checkpoint of `hash` at time t in out/checkpoint/.
void write_test_checkpoint(const fs::path& out, const std::string& hash, double t) {
  CheckpointManifest m;
  m.scene_hash = hash;
  m.time = t;
  m.step_index = 3;
  (void)write_checkpoint(out / "checkpoint", m, {{"ssa", ServiceBlob{"nsm", "state"}}});
}

TEST(ExitCodes, ExceptionsMapToTheDocumentedCodes) {
  EXPECT_EQ(exit_code_of(InvalidArgument("x")), kExitInvalidInput);
  EXPECT_EQ(exit_code_of(NumericalFailure("x")), kExitNumericalFailure);
  EXPECT_EQ(exit_code_of(Error(StatusCode::kUnavailable, "x")), kExitServiceFailure);
  EXPECT_EQ(exit_code_of(Error(StatusCode::kAborted, "x")), kExitInterrupted);
  EXPECT_EQ(exit_code_of(IoError("x")), kExitIoFailure);
  EXPECT_EQ(exit_code_of(std::runtime_error("x")), kExitServiceFailure);
}

/// start() counts the sessions; run() fails with `errors` in turn, then returns
/// the time of the checkpoint it resumed from (-1: none).
struct Fake {
  int starts = 0;
  std::vector<Error> errors;  ///< thrown as sadr::Error with their codes
  std::vector<const LoadedCheckpoint*> resumes;
  auto start() {
    ++starts;
    return std::make_unique<int>(starts);
  }
  double run(const LoadedCheckpoint* from) {
    resumes.push_back(from);
    if (resumes.size() <= errors.size()) throw errors[resumes.size() - 1];
    return from ? from->manifest.time : -1.0;
  }
  double go(const RestartPolicy& p, const fs::path& out, const LoadedCheckpoint* resume) {
    return run_with_restarts(
        p, 7, out, "h", resume, [this] { return start(); },
        [this](std::unique_ptr<int>&, const LoadedCheckpoint* from) { return run(from); });
  }
};

TEST(RestartPolicy, ServiceFailuresRestartUpToTheLimitFromTheLastCheckpoint) {
  const fs::path d = scratch("restart");
  Fake f;
  f.errors = {Error(StatusCode::kUnavailable, "fluid_service exited"),
              Error(StatusCode::kDeadlineExceeded, "no reply")};
  write_test_checkpoint(d, "h", 0.25);
  EXPECT_EQ(f.go({2, false}, d, nullptr), 0.25);  // the third attempt resumed at t = 0.25
  EXPECT_EQ(f.starts, 3);                         // a fresh session per attempt
  ASSERT_EQ(f.resumes.size(), 3u);
  EXPECT_EQ(f.resumes[0], nullptr);
  EXPECT_NE(f.resumes[1], nullptr);

  Fake once;
  once.errors = f.errors;
  try {
    once.go({1, false}, d, nullptr);
    ADD_FAILURE() << "a second service failure was restarted with --restart-on-failure 1";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), StatusCode::kDeadlineExceeded);
  }
  EXPECT_EQ(once.starts, 2);
  fs::remove_all(d);
}

TEST(RestartPolicy, OnlyServiceFailuresOfLocalServicesRestart) {
  const fs::path d = scratch("norestart");
  Fake bad_input;
  bad_input.errors = {InvalidArgument("bad scene")};
  try {
    bad_input.go({5, false}, d, nullptr);
    ADD_FAILURE() << "no exception";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), StatusCode::kInvalidArgument);
  }
  EXPECT_EQ(bad_input.starts, 1);
  Fake remote;
  remote.errors = {Error(StatusCode::kUnavailable, "gone")};
  EXPECT_THROW(remote.go({5, true}, d, nullptr), Error);
  EXPECT_EQ(remote.starts, 1);
  // A session that cannot start is not restarted.
  int starts = 0;
  EXPECT_THROW(run_with_restarts(
                   RestartPolicy{5, false}, 0, d, "h", nullptr,
                   [&starts]() -> std::unique_ptr<int> {
                     ++starts;
                     throw Error(StatusCode::kUnavailable, "cannot launch");
                   },
                   [](std::unique_ptr<int>&, const LoadedCheckpoint*) { return 0; }),
               Error);
  EXPECT_EQ(starts, 1);
  fs::remove_all(d);
}

TEST(RestartPolicy, WithoutACheckpointARestartBeginsWhereTheRunBegan) {
  const fs::path d = scratch("nocp");
  LoadedCheckpoint resumed;
  resumed.manifest.time = 0.5;
  Fake f;
  f.errors = {Error(StatusCode::kUnavailable, "gone")};
  EXPECT_EQ(f.go({1, false}, d, &resumed), 0.5);
  ASSERT_EQ(f.resumes.size(), 2u);
  EXPECT_EQ(f.resumes[1], &resumed);
  fs::remove_all(d);
}

TEST(RetryPolicy, FromZeroRemovesTheFailedAttemptsFiles) {
  const fs::path d = scratch("retry");
  int attempts = 0, before = 0;
  const auto failure = run_with_retries(
      RetryPolicy{1, false}, 3, d, "h", [&before] { ++before; },
      [&](const LoadedCheckpoint* resume) {
        EXPECT_EQ(resume, nullptr);
        if (++attempts == 1) {
          fs::create_directories(d / "frames");
          std::ofstream(d / "frames" / "frame_000000.csv") << "x";
          throw Error(StatusCode::kUnavailable, "died");
        }
        EXPECT_FALSE(fs::exists(d / "frames")) << "the failed attempt's frames stayed";
      },
      [] { return false; });
  EXPECT_FALSE(failure.has_value());
  EXPECT_EQ(attempts, 2);
  EXPECT_EQ(before, 2);
  fs::remove_all(d);
}

TEST(RetryPolicy, ExhaustedRetriesReturnTheLastFailure) {
  const fs::path d = scratch("exhausted");
  int attempts = 0;
  const auto failure = run_with_retries(
      RetryPolicy{2, false}, 5, d, "h", {},
      [&](const LoadedCheckpoint*) {
        ++attempts;
        throw NumericalFailure("blew up\nat step 3");
      },
      [] { return false; });
  ASSERT_TRUE(failure.has_value());
  EXPECT_EQ(attempts, 3);
  EXPECT_EQ(failure->realization, 5);
  EXPECT_EQ(failure->attempts, 3);
  EXPECT_EQ(failure->exit_code, kExitNumericalFailure);
  EXPECT_EQ(failure->reason, "blew up\nat step 3");
  // An interrupt ends the retries at once.
  attempts = 0;
  const auto stopped = run_with_retries(
      RetryPolicy{5, false}, 0, d, "h", {},
      [&](const LoadedCheckpoint*) {
        ++attempts;
        throw Error(StatusCode::kAborted, "stopped");
      },
      [] { return true; });
  ASSERT_TRUE(stopped.has_value());
  EXPECT_EQ(attempts, 1);
  EXPECT_EQ(stopped->exit_code, kExitInterrupted);
  fs::remove_all(d);
}

TEST(RetryPolicy, FromCheckpointResumesTheLastCheckpoint) {
  const fs::path d = scratch("retry-cp");
  write_test_checkpoint(d, "h", 0.75);
  std::vector<double> times;
  const auto failure = run_with_retries(
      RetryPolicy{1, true}, 0, d, "h", {},
      [&](const LoadedCheckpoint* resume) {
        times.push_back(resume ? resume->manifest.time : -1.0);
        if (times.size() == 1) throw Error(StatusCode::kUnavailable, "died");
      },
      [] { return false; });
  EXPECT_FALSE(failure.has_value());
  EXPECT_EQ(times, (std::vector<double>{0.75, 0.75}));
  EXPECT_TRUE(fs::exists(d / "checkpoint"));  // kept: the retry resumed from it
  fs::remove_all(d);
}

}  // namespace
}  // namespace sadr::orchestrator
