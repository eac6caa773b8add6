// SPDX-License-Identifier: MIT
// Scene overrides end to end (`sadr run --set`, run.json, resume), and sweeps.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

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

}  // namespace
}  // namespace sadr::orchestrator
