// SPDX-License-Identifier: MIT
// sadr::orchestrator_campaign: the aggregation at the end of a sweep (done,
// incomplete and refused points, the keep policy, observables.csv) and the
// figures and text of `sadr summary`.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "runs_test_support.hpp"
#include "sadr/common/status.hpp"
#include "sadr/orchestrator/frame_writers.hpp"
#include "sadr/orchestrator/run_summary.hpp"
#include "sadr/orchestrator/scene_loader.hpp"
#include "sadr/orchestrator/summary_totals.hpp"
#include "sadr/orchestrator/sweep_aggregation.hpp"
#include "sadr/orchestrator/sweep_spec.hpp"

namespace sadr::orchestrator {
namespace {
namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  return runs_test::scratch("sadr-runs2", name);
}
using runs_test::read_all;

/// Frames 0 and 1 of 3 particles (density 2, mass 0.5: volume 0.25) with A = base + k.
void write_frames(const fs::path& rd, double base) {
  fs::create_directories(rd / "frames");
  ParticleState p;
  p.dimension = 1;
  p.resize(3);
  for (std::size_t i = 0; i < 3; ++i) {
    p.ids[i] = i;
    p.positions[3 * i] = 0.25 * static_cast<double>(i);
    p.densities[i] = 2.0;
    p.masses[i] = 0.5;
  }
  for (int k = 0; k < 2; ++k) {
    const std::vector<SpeciesColumn> a{{"A", {base + k, base + k, 2.0 * (base + k)}}};
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06d.csv", k);
    write_frame_csv(rd / "frames" / name, 0.5 * k, p, a);
  }
}

TEST(SweepAggregation, CsvFieldsAreQuotedOnlyWhenNeeded) {
  EXPECT_EQ(csv_field("rate"), "rate");
  EXPECT_EQ(csv_field("a,b"), "\"a,b\"");
  EXPECT_EQ(csv_field("say \"x\""), "\"say \"\"x\"\"\"");
}

TEST(SweepAggregation, CompletePointsAggregateOthersAreIncompleteOrRefused) {
  const fs::path d = scratch("sweep");
  const fs::path scene = fs::path(SADR_SOURCE_DIR) / "examples" / "static_reaction_diffusion.yaml";
  const SweepSpec spec = parse_sweep_spec("scene: " + scene.string() +
                                              "\nrealizations: 2\nparameters:\n  grid:\n"
                                              "    species[0].diffusivity: [0.01, 0.02]\n",
                                          d / "sweep.yaml");
  SweepManifest m = SweepManifest::plan(spec, 7);
  ASSERT_EQ(m.runs.size(), 4u);
  for (SweepRun& run : m.runs) {
    run.state = RunState::kOk;
    run.scene_hash = load_scene(m.base_scene, m.overrides_of(run)).source_hash;
    write_frames(d / run.dir, static_cast<double>(run.index));
  }
  m.runs[3].state = RunState::kFailed;  // point 1, realization 1
  m.runs[3].reason = "service died\ndetails";
  aggregate_sweep(m, d, true);
  ASSERT_EQ(m.aggregates["0"].value("state", ""), "done") << m.aggregates.dump();
  EXPECT_EQ(m.aggregates["0"].value("realizations", 0), 2);
  EXPECT_EQ(m.aggregates["1"].value("state", ""), "incomplete");
  EXPECT_EQ(m.aggregates["1"]["notes"][0], "1 of 2 runs finished; not aggregated");
  EXPECT_TRUE(fs::exists(d / point_dir(0) / "observables.csv"));
  EXPECT_FALSE(fs::exists(d / point_dir(1) / "observables.csv"));
  // keep: aggregates (the default): the frames of every realization but the first go.
  EXPECT_TRUE(fs::exists(d / m.runs[0].dir / "frames"));
  EXPECT_FALSE(fs::exists(d / m.runs[1].dir / "frames"));
  EXPECT_EQ(m.runs[1].kept, "run.json, result.json, worker.log");
  const std::string obs = read_all(d / "observables.csv");
  EXPECT_EQ(obs.substr(0, obs.find('\n')),
            "point,realization,species[0].diffusivity,frame,time,species,total");
  // Realization 1 of point 0: A = 1 + k on 3 particles (1, 1, 2) -> total 4 at frame 0.
  EXPECT_NE(obs.find("\n0,1,0.01,0,0,A,4\n"), std::string::npos) << obs;
  EXPECT_EQ(print_sweep_failures(m), 1u);

  // Point 1 completes, but its runs ran different scenes: refused. Point 0 stays done
  // although its frames are gone.
  m.runs[3].state = RunState::kOk;
  m.runs[3].scene_hash = "another";
  aggregate_sweep(m, d, true);
  EXPECT_EQ(m.aggregates["1"].value("state", ""), "refused");
  EXPECT_EQ(m.aggregates["0"].value("state", ""), "done");
  EXPECT_EQ(print_sweep_failures(m), 0u);
  EXPECT_EQ(read_all(d / "observables.csv"), obs);
  fs::remove_all(d);
}

TEST(RunSummary, ColumnTotalsAndAmounts) {
  const fs::path d = scratch("totals");
  write_frames(d, 1.0);
  const ColumnTotals t = sum_columns(d / "frames" / "frame_000001.csv", false);
  EXPECT_EQ(t.time, 0.5);
  ASSERT_EQ(t.names, std::vector<std::string>{"A"});
  EXPECT_DOUBLE_EQ(t.totals[0], 2.0 + 2.0 + 4.0);
  EXPECT_DOUBLE_EQ(t.amounts[0], 8.0 * 0.25);  // value x mass / density
  std::ofstream(d / "bad.csv") << "time,id\n0,1,2\n";
  EXPECT_THROW((void)sum_columns(d / "bad.csv", false), InvalidArgument);

  ManifestTotals m;
  m.add(nlohmann::json{{"steps", 10},
                       {"fluid_substeps", 30},
                       {"ssa_events", 5},
                       {"time", 1.0},
                       {"timings_s", {{"fluid", 0.5}}},
                       {"status", "ok"}});
  m.add(nlohmann::json{{"steps", 4}, {"time", 2.0}, {"timings_s", {{"fluid", 0.25}}}});
  EXPECT_EQ(m.steps, 14);
  EXPECT_EQ(m.substeps, 30);
  EXPECT_EQ(m.time, 2.0);
  EXPECT_FALSE(m.events_recorded);  // the second manifest has no ssa_events
  EXPECT_DOUBLE_EQ(m.timings.at("fluid"), 0.75);
  EXPECT_EQ(m.statuses, (std::vector<std::string>{"ok", "?"}));
  fs::remove_all(d);
}

std::string summary_of(const fs::path& dir) {
  std::FILE* f = std::tmpfile();
  print_summary(dir, f);
  std::rewind(f);
  std::string text;
  for (int c; (c = std::fgetc(f)) != EOF;) text.push_back(static_cast<char>(c));
  std::fclose(f);
  return text;
}

TEST(RunSummary, ARunsSummaryHasItsCountersAndSpeciesTotals) {
  const fs::path d = scratch("summary");
  write_frames(d, 1.0);
  std::ofstream(d / "run.json") << R"({"scene_path": "/nonexistent/scene.yaml",
    "scene_hash": "h1", "realization": 3, "seed": 42, "status": "ok", "mode": "embedded",
    "steps": 10, "fluid_substeps": 20, "overlapped_steps": 0, "ssa_events": 1234, "time": 1,
    "timings_s": {"fluid": 1.5, "ssa": 0.25}, "plan": {"fluid_species": []},
    "frames": ["frames/frame_000000.csv", "frames/frame_000001.csv"]})";
  const std::string s = summary_of(d);
  EXPECT_NE(s.find("sadr summary: " + d.string() + "\n"), std::string::npos) << s;
  EXPECT_NE(s.find("  run: realization 3, seed 42, status ok, embedded\n"), std::string::npos) << s;
  EXPECT_NE(s.find("  t = 1: 10 coupling steps, 20 fluid sub-steps (2.00 per step), 0 overlapped"),
            std::string::npos)
      << s;
  EXPECT_NE(s.find("  SSA events: 1234 (reactions + diffusion jumps)"), std::string::npos) << s;
  char row[128];
  std::snprintf(row, sizeof row, "    %-32s %22.10g  %22.10g\n", "A", 4.0, 8.0);
  EXPECT_NE(s.find(row), std::string::npos) << s;
  EXPECT_NE(s.find("(2 files)"), std::string::npos) << s;
  // Neither a run nor an ensemble.
  fs::remove(d / "run.json");
  EXPECT_THROW((void)summary_of(d), InvalidArgument);
  fs::remove_all(d);
}

}  // namespace
}  // namespace sadr::orchestrator
