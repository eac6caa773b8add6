// SPDX-License-Identifier: MIT
// sadr::orchestrator_campaign: the reorder buffer, the ensemble pool (out-of-order
// completion added in order), and the ensemble manifest (write, read, resume).
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <mutex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "runs_test_support.hpp"
#include "sadr/orchestrator/ensemble_manifest.hpp"
#include "sadr/orchestrator/ensemble_pool.hpp"
#include "sadr/orchestrator/reorder_buffer.hpp"
#include "sadr/orchestrator/run_manifest.hpp"

namespace sadr::orchestrator {
namespace {
namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  return runs_test::scratch("sadr-runs", name);
}
using runs_test::read_all;

TEST(ReorderBuffer, OutOfOrderCompletionIsHandedOnInIndexOrder) {
  std::vector<std::pair<int, std::string>> seen;
  ReorderBuffer<std::string> buffer(
      [&seen](int i, std::string& item) { seen.emplace_back(i, item); });
  buffer.complete(2, "c");
  buffer.complete(1, "b");
  EXPECT_TRUE(seen.empty());  // 0 is missing: nothing may pass it
  EXPECT_EQ(buffer.waiting(), 2u);
  EXPECT_EQ(buffer.next(), 0);
  buffer.complete(0, "a");
  buffer.complete(4, "e");
  const std::vector<std::pair<int, std::string>> in_order{{0, "a"}, {1, "b"}, {2, "c"}};
  EXPECT_EQ(seen, in_order);
  EXPECT_EQ(buffer.next(), 3);
  EXPECT_EQ(buffer.waiting(), 1u);  // 4 waits for 3
  buffer.complete(3, "d");
  ASSERT_EQ(seen.size(), 5u);
  EXPECT_EQ(seen[3].second, "d");
  EXPECT_EQ(seen[4].second, "e");
  EXPECT_EQ(buffer.waiting(), 0u);
}

/// Frame 0 of realization r: values whose floating-point sums depend on the order.
RealizationFrames frames_of(int r) {
  RealizationFrames f;
  const double v = r % 2 == 0 ? 1e16 * (r + 1) : 0.1 * r + 1e-3;
  f[0] = {0.5, {SpeciesColumn{"A", {v, 3.0 * v}}}};
  return f;
}

std::string ensemble_csv(const EnsembleAccumulator& acc, const fs::path& dir) {
  write_ensemble_frames(acc, dir, std::vector<std::uint64_t>{});
  return read_all(dir / "ensemble" / "frame_000000.csv");
}

TEST(EnsemblePool, RealizationsFinishingInReverseAreAddedInIndexOrder) {
  const fs::path d = scratch("pool");
  constexpr int kCount = 5;
  std::mutex mutex;
  std::vector<int> finished;
  EnsembleAccumulator pooled({"A"}, 2);
  const std::atomic<bool> interrupt{false};
  const PoolResult res = run_ensemble_pool(pooled, kCount, kCount, true, interrupt, [&](int r) {
    // The later the index, the sooner it finishes.
    std::this_thread::sleep_for(std::chrono::milliseconds(40 * (kCount - r)));
    {
      std::lock_guard lock(mutex);
      finished.push_back(r);
    }
    MemberResult m;
    m.frames = frames_of(r);
    return m;
  });
  EXPECT_EQ(res.done, kCount);
  EXPECT_TRUE(res.failed.empty());
  ASSERT_EQ(finished.size(), static_cast<std::size_t>(kCount));
  EXPECT_NE(finished.front(), 0) << "the realizations did not finish out of order";
  EXPECT_EQ(pooled.realizations(0), static_cast<std::size_t>(kCount));

  EnsembleAccumulator in_order({"A"}, 2), reversed({"A"}, 2);
  for (int r = 0; r < kCount; ++r) {
    const auto f = frames_of(r);
    in_order.add(0, f.at(0).first, f.at(0).second);
    const auto g = frames_of(kCount - 1 - r);
    reversed.add(0, g.at(0).first, g.at(0).second);
  }
  const std::string want = ensemble_csv(in_order, d / "in_order");
  // The values are chosen so that the order shows in the files.
  ASSERT_NE(want, ensemble_csv(reversed, d / "reversed"));
  EXPECT_EQ(ensemble_csv(pooled, d / "pooled"), want);
  fs::remove_all(d);
}

TEST(EnsemblePool, FailedRealizationsAreSortedAndAddNothing) {
  EnsembleAccumulator acc({"A"}, 2);
  const std::atomic<bool> interrupt{false};
  const PoolResult res = run_ensemble_pool(acc, 6, 3, true, interrupt, [](int r) {
    MemberResult m;
    if (r == 4 || r == 1) {
      m.failure = FailedRealization{r, 3, "service died", 2};
    } else {
      m.frames = frames_of(r);
    }
    return m;
  });
  EXPECT_EQ(res.done, 4);
  ASSERT_EQ(res.failed.size(), 2u);
  EXPECT_EQ(res.failed[0].realization, 1);
  EXPECT_EQ(res.failed[1].realization, 4);
  EXPECT_EQ(res.failed[1].attempts, 2);
  EXPECT_EQ(acc.realizations(0), 4u);  // the ones after a failure are still added
}

TEST(EnsemblePool, AnInterruptStopsTakingRealizations) {
  EnsembleAccumulator acc({"A"}, 2);
  std::atomic<bool> interrupt{false};
  std::atomic<int> started{0};
  const PoolResult res = run_ensemble_pool(acc, 10, 1, true, interrupt, [&](int r) {
    ++started;
    if (r == 2) interrupt = true;
    MemberResult m;
    m.frames = frames_of(r);
    return m;
  });
  EXPECT_EQ(started.load(), 3);
  EXPECT_EQ(res.done, 3);
}

TEST(EnsembleManifest, WriteReadRoundTripAndResumeList) {
  const fs::path d = scratch("manifest");
  EnsembleManifest m;
  m.scene_path = "/abs/scene.yaml";
  m.overrides = {"reactions[a].rate=0.2"};
  m.scene_hash = "abc123";
  m.realizations = 4;
  m.retries = 2;
  m.failed = {{1, 3, "service died\nmore", 3}};
  EXPECT_FALSE(is_ensemble_dir(d));
  m.write(d);
  EXPECT_TRUE(is_ensemble_dir(d));
  const std::string text = read_all(d / "ensemble.json");
  EXPECT_NE(text.find("\"format\": \"sadr-ensemble\""), std::string::npos) << text;
  const EnsembleManifest back = EnsembleManifest::read(d);
  EXPECT_EQ(back.scene_path, m.scene_path);
  EXPECT_EQ(back.overrides, m.overrides);
  EXPECT_EQ(back.scene_hash, m.scene_hash);
  EXPECT_EQ(back.realizations, 4);
  EXPECT_EQ(back.retries, 2);
  ASSERT_EQ(back.failed.size(), 1u);
  EXPECT_EQ(back.failed[0].realization, 1);
  EXPECT_EQ(back.failed[0].exit_code, 3);
  EXPECT_EQ(back.failed[0].reason, "service died\nmore");
  EXPECT_EQ(back.failed[0].attempts, 3);
  fs::create_directories(d / "again");
  back.write(d / "again");
  EXPECT_EQ(read_all(d / "again" / "ensemble.json"), text);  // byte-identical

  // Realization 0 finished, 1 failed, 2 is absent, 3 stopped at a checkpoint.
  const auto run_json = [&](int r, const std::string& status) {
    const fs::path rd = d / realization_dir_name(static_cast<std::uint64_t>(r));
    fs::create_directories(rd);
    std::ofstream(rd / "run.json") << "{\"status\": \"" << status << "\"}";
  };
  run_json(0, "ok");
  run_json(1, "failed");
  run_json(3, "interrupted");
  EXPECT_TRUE(realization_finished(d / "realization_0000"));
  EXPECT_FALSE(realization_finished(d / "realization_0002"));
  EXPECT_EQ(unfinished_realizations(d, 4), (std::vector<int>{1, 2, 3}));
  fs::remove_all(d);
}

TEST(EnsembleManifest, RealizationFoldersHaveOneName) {
  EXPECT_EQ(realization_dir_name(0), "realization_0000");
  EXPECT_EQ(realization_dir_name(42), "realization_0042");
  EXPECT_EQ(realization_dir_name(12345), "realization_12345");
  for (const std::uint64_t r : {0u, 7u, 9999u, 12345u}) {
    EXPECT_TRUE(is_realization_dir_name(realization_dir_name(r))) << r;
  }
  EXPECT_FALSE(is_realization_dir_name("realization_12"));
  EXPECT_FALSE(is_realization_dir_name("realization_00a1"));
  EXPECT_FALSE(is_realization_dir_name("ensemble"));
}

TEST(EnsembleManifest, AMissingKeyIsNamed) {
  const fs::path d = scratch("manifest-bad");
  std::ofstream(d / "ensemble.json") << R"({"overrides": [], "scene_path": "s.yaml"})";
  try {
    (void)EnsembleManifest::read(d);
    ADD_FAILURE() << "a manifest without scene_hash was read";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("scene_hash"), std::string::npos) << e.what();
  }
  fs::remove_all(d);
}

}  // namespace
}  // namespace sadr::orchestrator
