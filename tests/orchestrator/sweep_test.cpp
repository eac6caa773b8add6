// SPDX-License-Identifier: MIT
// Sweep files (grid, zip, points, errors), the manifest's seeds and round
// trip, and the per-point aggregation of synthetic run directories (velocity
// and density aggregated only where they vary, positions note, missing frames).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "sadr/common/status.hpp"
#include "sadr/orchestrator/frame_writers.hpp"
#include "sadr/orchestrator/sweep_aggregate.hpp"
#include "sadr/orchestrator/sweep_frames.hpp"
#include "sadr/orchestrator/sweep_manifest.hpp"
#include "sadr/orchestrator/sweep_spec.hpp"

namespace sadr::orchestrator {
namespace {
namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("sadr-sweep-" + std::to_string(getpid()) + name);
  fs::remove_all(d);
  fs::create_directories(d);
  std::ofstream(d / "scene.yaml") << "dimension: 1\n";
  return d;
}

std::string read_all(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string read_frame_header(const fs::path& p) {
  const std::string t = read_all(p);
  return t.substr(0, t.find('\n'));
}

SweepSpec spec(const fs::path& d, const std::string& body) {
  return parse_sweep_spec("scene: scene.yaml\n" + body, d / "sweep.yaml");
}

std::string error_of(const fs::path& d, const std::string& body) {
  try {
    spec(d, body);
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SweepSpec, GridIsACartesianProductTimesTheZippedRows) {
  const fs::path d = scratch("grid");
  const SweepSpec s = spec(d,
                           "realizations: 3\nparameters:\n  grid:\n    a.x: [1, 2]\n"
                           "    b[0].y: [10, 20, 30]\n  zip:\n    c: [[0.1, 0.2], [0.3]]\n"
                           "    d: [u, v]\n");
  EXPECT_EQ(s.parameters, (std::vector<std::string>{"a.x", "b[0].y", "c", "d"}));
  ASSERT_EQ(s.points.size(), 2u * 3u * 2u);
  // The zip varies fastest, then the last grid path.
  EXPECT_EQ(s.points[0].overrides[0].text(), "a.x=1");
  EXPECT_EQ(s.points[0].overrides[2].text(), "c=[0.1, 0.2]");
  EXPECT_EQ(s.points[1].overrides[3].text(), "d=v");
  EXPECT_EQ(s.points[2].overrides[1].text(), "b[0].y=20");
  EXPECT_EQ(s.points[11].overrides[0].text(), "a.x=2");
  EXPECT_EQ(s.keep, KeepPolicy::kAggregates);
  EXPECT_EQ(s.executor.type, "local");
  fs::remove_all(d);
}

TEST(SweepSpec, ProblemsAreReportedWithLineAndKey) {
  const fs::path d = scratch("errors");
  EXPECT_NE(error_of(d, "parameters:\n  zip:\n    a: [1, 2]\n    b: [1]\n")
                .find("zipped lists must have equal lengths"),
            std::string::npos);
  EXPECT_NE(error_of(d, "realisations: 2\n").find("did you mean 'realizations'?"),
            std::string::npos);
  EXPECT_NE(error_of(d, "executor: {type: pbs}\n").find("unknown executor 'pbs'"),
            std::string::npos);
  EXPECT_NE(error_of(d, "keep: some\n").find("unknown keep policy 'some'"), std::string::npos);
  EXPECT_NE(error_of(d, "parameters:\n  grid:\n    a..b: [1]\n").find("empty key"),
            std::string::npos);
  EXPECT_NE(error_of(d, "parameters:\n  points:\n    - {a: 1}\n    - {b: 2}\n")
                .find("every point must set the same paths"),
            std::string::npos);
  EXPECT_NE(error_of(d, "realizations: 0\n").find("realizations"), std::string::npos);
  fs::remove_all(d);
}

TEST(SweepManifest, SeedsDependOnSweepSeedPointAndRealizationAndRoundTrip) {
  const fs::path d = scratch("manifest");
  const SweepSpec s = spec(
      d, "realizations: 4\nparameters:\n  points:\n    - {a: 1}\n    - {a: 2}\n    - {a: 3}\n");
  const SweepManifest m = SweepManifest::plan(s, 7);
  ASSERT_EQ(m.runs.size(), 12u);
  std::set<std::uint64_t> seeds;
  for (const auto& r : m.runs) seeds.insert(r.seed);
  EXPECT_EQ(seeds.size(), 12u);
  EXPECT_NE(SweepManifest::plan(s, 8).runs[5].seed, m.runs[5].seed);
  EXPECT_EQ(SweepManifest::plan(s, 7).runs[5].seed, m.runs[5].seed);
  EXPECT_EQ(m.runs[6].dir, "runs/p0001_r0002");
  EXPECT_EQ(m.overrides_of(m.runs[6]).back().text(), "seed=" + std::to_string(m.point_seeds[1]));
  m.write(d);
  const SweepManifest back = SweepManifest::read(d);
  EXPECT_TRUE(back.same_runs(m));
  EXPECT_EQ(back.to_json(), m.to_json());
  EXPECT_THROW((void)m.run(12), InvalidArgument);
  EXPECT_TRUE(back.flows.empty());  // not decided: every run steps its own fluid
  // The flow replay decision per point round-trips; the file of a key is under flows/.
  SweepManifest f = m;
  f.flows = {{true, "fnv1a64:0123456789abcdef", "shared"},
             {false, "", "thermal noise"},
             {true, "fnv1a64:0123456789abcdef", "shared"}};
  f.write(d);
  const SweepManifest g = SweepManifest::read(d);
  ASSERT_EQ(g.flows.size(), 3u);
  EXPECT_TRUE(g.flows[2].replay);
  EXPECT_EQ(g.flows[1].reason, "thermal noise");
  EXPECT_EQ(g.to_json(), f.to_json());
  EXPECT_EQ(flow_tape_file(g.flows[0].fluid_key), "flows/0123456789abcdef.bin");
  fs::remove_all(d);
}

/// A run directory with frames 0 and 1 of 3 particles; `noise` shifts the
/// velocities (a thermal fluid), `moved` the positions.
fs::path fake_run(const fs::path& d, int r, double noise, double moved, bool second_frame = true) {
  const fs::path rd = d / ("r" + std::to_string(r));
  fs::create_directories(rd / "frames");
  ParticleState p;
  p.dimension = 1;
  p.resize(3);
  for (std::size_t i = 0; i < 3; ++i) {
    p.ids[i] = i;
    p.positions[3 * i] = 0.25 * static_cast<double>(i) + moved;
    p.velocities[3 * i] = noise * static_cast<double>(i + 1);
    p.densities[i] = 1.0;
    p.masses[i] = 0.25;
  }
  for (int k = 0; k < (second_frame ? 2 : 1); ++k) {
    const std::vector<SpeciesColumn> a{{"A", {double(r + k), double(2 * r), 3.0}}};
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06d.csv", k);
    write_frame_csv(rd / "frames" / name, 0.5 * k, p, a);
  }
  return rd;
}

TEST(SweepAggregate, VelocityOnlyWhereItVariesPositionsNotedMissingFramesRefused) {
  const fs::path d = scratch("aggregate");
  const std::vector<std::string> prefixes{"0,0", "0,1", "0,2"};
  std::ostringstream obs;
  const std::vector<fs::path> still{fake_run(d / "a", 0, 0, 0), fake_run(d / "a", 1, 0, 0),
                                    fake_run(d / "a", 2, 0, 0)};
  const PointAggregate a = aggregate_point(still, prefixes, d / "out_a", "agg", obs);
  EXPECT_EQ(a.realizations, 3u);
  EXPECT_EQ(a.frames, 2u);
  EXPECT_TRUE(a.positions_identical);
  EXPECT_FALSE(a.fluid_columns);
  const std::string csv = read_frame_header(d / "out_a" / "frame_000001.csv");
  EXPECT_EQ(csv, "time,id,realizations,x,y,z,A_mean,A_var,A_sem,A_ci95_lo,A_ci95_hi");
  // A = r + 1 at particle 0 of frame 1: mean 2, var 1, sem 1/sqrt(3).
  EXPECT_NE(read_all(d / "out_a" / "frame_000001.csv").find("\n0.5,0,3,0,0,0,2,1,"),
            std::string::npos)
      << read_all(d / "out_a" / "frame_000001.csv");
  EXPECT_TRUE(fs::exists(d / "out_a" / "agg.pvd"));
  EXPECT_NE(obs.str().find("0,2,1,0.5,A,"), std::string::npos) << obs.str();

  const std::vector<fs::path> thermal{fake_run(d / "b", 0, 0.1, 0), fake_run(d / "b", 1, 0.2, 0.01),
                                      fake_run(d / "b", 2, 0.3, 0)};
  const PointAggregate b = aggregate_point(thermal, prefixes, d / "out_b", "agg", obs);
  EXPECT_TRUE(b.fluid_columns);
  EXPECT_FALSE(b.positions_identical);
  ASSERT_EQ(b.notes.size(), 1u);
  EXPECT_NE(b.notes[0].find("realization 0's positions"), std::string::npos);
  EXPECT_NE(read_frame_header(d / "out_b" / "frame_000000.csv").find(",vx_mean,"),
            std::string::npos);

  const std::vector<fs::path> gap{fake_run(d / "c", 0, 0, 0), fake_run(d / "c", 1, 0, 0, false),
                                  fake_run(d / "c", 2, 0, 0)};
  try {
    aggregate_point(gap, prefixes, d / "out_c", "agg", obs);
    ADD_FAILURE() << "a missing frame was averaged over fewer realizations";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("frame 1 is missing"), std::string::npos) << e.what();
  }
  fs::remove_all(d);
}

TEST(SweepAggregate, StudentTQuantile) {
  EXPECT_NEAR(t95(2), 12.706204736174698, 1e-12);
  // mpmath (30 digits): 2.26215716279820550864...; scipy 1.10's t.ppf gives
  // 2.2621571627409915, 5.7e-11 off.
  EXPECT_NEAR(t95(10), 2.2621571627982055, 1e-14);
  EXPECT_TRUE(std::isnan(t95(1)));
}

}  // namespace
}  // namespace sadr::orchestrator
