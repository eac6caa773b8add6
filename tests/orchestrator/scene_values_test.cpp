// SPDX-License-Identifier: MIT
// Scene keys for per-particle data: initial species values from columns of
// the particle CSV, regions given as particle id lists, and the refusals that
// go with them (duplicate or empty CSV headers, empty initial regions).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "sadr/common/status.hpp"
#include "sadr/orchestrator/scene_loader.hpp"
#include "scene_test_support.hpp"

namespace sadr::orchestrator {
namespace {

/// A scratch directory with a particle CSV; removed at the end of the test.
class ParticleFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        std::filesystem::temp_directory_path() /
        ("sadr_scene_values_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
         "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  void write_csv(const std::string& text) const {
    std::ofstream(dir_ / "cloud.csv", std::ios::binary) << text;
  }
  /// A 1D scene on cloud.csv with the given species section.
  [[nodiscard]] Scene parse(const std::string& species, const std::string& regions = "") const {
    const std::string text =
        "dimension: 1\n"
        "box: {lower: [0.0], upper: [1.0]}\n" +
        regions +
        "particles: {file: cloud.csv}\n"
        "fluid: {backend: static, smoothing_length: 0.3}\n" +
        species + "time: {coupling_step: 0.1, end: 1.0}\n";
    return parse_scene(text, dir_ / "scene.yaml");
  }
  [[nodiscard]] std::string error_of(const std::string& species,
                                     const std::string& regions = "") const {
    try {
      (void)parse(species, regions);
    } catch (const InvalidArgument& e) {
      return e.what();
    }
    return "<no error>";
  }

  std::filesystem::path dir_;
};

// Volumes m / rho: 0.25, 0.25, 0.5, 0.25.
const std::string kCloud =
    "x,y,z,mass,density,kind,A0,cB\n"
    "0.0,0,0,0.25,1,wall,3,1.5\n"
    "0.25,0,0,0.25,1,fluid,0,2\n"
    "0.5,0,0,0.5,1,fluid,7,4\n"
    "1.0,0,0,0.25,1,wall,1,0\n";
// The same particles with only the A0 column (an unread column is refused).
const std::string kCloudA0 =
    "x,y,z,mass,density,kind,A0\n"
    "0.0,0,0,0.25,1,wall,3\n"
    "0.25,0,0,0.25,1,fluid,0\n"
    "0.5,0,0,0.5,1,fluid,7\n"
    "1.0,0,0,0.25,1,wall,1\n";

TEST_F(ParticleFile, InitialValuesFromColumnsCountsAndConcentrations) {
  write_csv(kCloud);
  const Scene s = parse(
      "species:\n"
      "  - {name: A, diffusivity: 0.1, initial: [{count_column: A0}]}\n"
      "  - {name: B, stochastic: false, diffusivity: 0.1, initial: [{concentration_column: cB}]}\n"
      "  - {name: C, stochastic: false, diffusivity: 0.1, initial: [{count_column: A0}]}\n"
      "  - {name: D, diffusivity: 0.1, initial: [{concentration_column: cB}]}\n");
  EXPECT_EQ(s.find_species("A")->initial, (std::vector<double>{3, 0, 7, 1}));
  EXPECT_EQ(s.find_species("B")->initial, (std::vector<double>{1.5, 2, 4, 0}));
  // a count in a deterministic species becomes count / V
  EXPECT_EQ(s.find_species("C")->initial, (std::vector<double>{12, 0, 14, 4}));
  // a concentration in a stochastic species becomes round(C V)
  EXPECT_EQ(s.find_species("D")->initial, (std::vector<double>{0, 1, 2, 0}));
}

TEST_F(ParticleFile, ColumnInitialComposesWithRegionsInOrder) {
  write_csv(kCloudA0);
  const Scene s = parse(
      "species:\n"
      "  - name: A\n"
      "    diffusivity: 0.1\n"
      "    initial: [{count: 9}, {region: picked, count_column: A0}]\n",
      "regions: [{name: picked, shape: ids, ids: [3, 2]}]\n");
  EXPECT_EQ(s.find_species("A")->initial, (std::vector<double>{9, 9, 7, 1}));
}

TEST_F(ParticleFile, IdRegionsSelectByIdAndKind) {
  write_csv(kCloudA0);
  const Scene s = parse(
      "species:\n"
      "  - name: A\n"
      "    diffusivity: 0.1\n"
      "    initial: [{count_column: A0}]\n"
      "    boundaries: [{region: ends, condition: dirichlet, value: 8}]\n",
      "regions:\n"
      "  - {name: three, shape: ids, ids: [0, 1, 3]}\n"
      "  - {name: ends, shape: ids, ids: [0, 1, 3], kinds: [wall]}\n");
  EXPECT_EQ(s.find_region("three")->particles, (std::vector<std::uint32_t>{0, 1, 3}));
  EXPECT_EQ(s.find_region("ends")->particles, (std::vector<std::uint32_t>{0, 3}));
  // Dirichlet walls start at round(8 * 0.25) = 2 over the column's values
  EXPECT_EQ(s.find_species("A")->initial, (std::vector<double>{2, 0, 7, 2}));
}

TEST_F(ParticleFile, BadIdListsAreRefused) {
  write_csv(kCloud);
  const std::string m = error_of("",
                                 "regions:\n"
                                 "  - {name: far, shape: ids, ids: [1, 4]}\n"
                                 "  - {name: twice, shape: ids, ids: [2, 2]}\n"
                                 "  - {name: frac, shape: ids, ids: [0.5]}\n"
                                 "  - {name: none, shape: ids, ids: []}\n"
                                 "  - {name: geo, shape: ids, ids: [1], radius: 0.1}\n");
  EXPECT_NE(m.find("regions[0].ids: particle id 4 of region 'far' does not exist; allowed: ids 0 "
                   "to 3 (4 particles)"),
            std::string::npos)
      << m;
  EXPECT_NE(m.find("regions[1].ids[1]: particle id 2 is listed twice"), std::string::npos) << m;
  EXPECT_NE(m.find("regions[2].ids[0]: 0.5 is not a particle id"), std::string::npos) << m;
  EXPECT_NE(m.find("regions[3].ids: expected a non-empty list"), std::string::npos) << m;
  EXPECT_NE(m.find("key 'radius' does not apply to shape 'ids'"), std::string::npos) << m;
}

TEST(IdRegion, CannotFillALattice) {
  const std::string text = test::replace_once(
      test::kBaseScene, "  - {name: left, shape: box, lower: [0.0], upper: [0.0]}\n",
      "  - {name: left, shape: ids, ids: [0]}\n");
  try {
    (void)parse_scene(text, "scene.yaml");
    FAIL() << "accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("particles.fill[0].region: region 'left' lists particle "
                                         "ids, which do not exist before the lattice is filled"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(ParticleFile, BadColumnValuesAreNamedByFileAndLine) {
  write_csv(
      "x,y,z,mass,density,kind,A0\n"
      "0.0,0,0,0.25,1,wall,3\n"
      "0.5,0,0,0.25,1,fluid,-2\n"
      "1.0,0,0,0.25,1,fluid,1.5\n");
  const std::string m =
      error_of("species: [{name: A, diffusivity: 0.1, initial: [{count_column: A0}]}]\n");
  EXPECT_NE(m.find("cloud.csv:3: column 'A0': -2 is out of range; allowed: >= 0"),
            std::string::npos)
      << m;
  EXPECT_NE(m.find("cloud.csv:4: column 'A0': 1.5 is not allowed for the stochastic species 'A'"),
            std::string::npos)
      << m;
  EXPECT_NE(m.find("species[0].initial[0].count_column:"), std::string::npos) << m;
}

TEST_F(ParticleFile, UnknownAndUnreadColumnsAreRefused) {
  write_csv(kCloud);
  const std::string m =
      error_of("species: [{name: A, diffusivity: 0.1, initial: [{count_column: A1}]}]\n");
  EXPECT_NE(m.find("has no column 'A1'; did you mean 'A0'? (value columns: A0, cB)"),
            std::string::npos)
      << m;
  // neither column is read by any species
  EXPECT_NE(m.find("cloud.csv:1: unknown column 'A0'"), std::string::npos) << m;
  EXPECT_NE(m.find("cloud.csv:1: unknown column 'cB'"), std::string::npos) << m;
}

TEST_F(ParticleFile, DuplicateColumnIsRefused) {
  write_csv("x,y,z,mass,density,kind,x\n0.5,0,0,0.25,1,fluid,0.5\n");
  const std::string m = error_of("");
  EXPECT_NE(m.find("cloud.csv:1: column 'x' appears twice (columns 1 and 7)"), std::string::npos)
      << m;
}

TEST_F(ParticleFile, EmptyAndHeaderOnlyFilesHaveClearMessages) {
  write_csv("");
  std::string m = error_of("");
  EXPECT_NE(m.find("cloud.csv:1: empty header row"), std::string::npos) << m;
  EXPECT_NE(m.find(": 1 problem\n"), std::string::npos) << m;
  write_csv("x,y,z,mass,density,kind\n");
  m = error_of("");
  EXPECT_NE(m.find("cloud.csv:2: no particle rows after the header"), std::string::npos) << m;
  EXPECT_NE(m.find(": 1 problem\n"), std::string::npos) << m;
}

TEST_F(ParticleFile, InitialOnAnEmptyRegionIsAnError) {
  write_csv(kCloud);
  const std::string m =
      error_of("species: [{name: A, diffusivity: 0.1, initial: [{region: gap, count: 2}]}]\n",
               "regions: [{name: gap, shape: box, lower: [0.6], upper: [0.9]}]\n");
  EXPECT_NE(m.find("species[0].initial[0].region: region 'gap' holds no particle"),
            std::string::npos)
      << m;
}

TEST(ColumnInitial, NeedsAParticleFile) {
  const std::string text = test::replace_once(test::kBaseScene, "    diffusivity: 0.2\n",
                                              "    diffusivity: 0.2\n"
                                              "    initial: [{count_column: B0}]\n");
  try {
    (void)parse_scene(text, "scene.yaml");
    FAIL() << "accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("needs a particle file (particles.file)"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace sadr::orchestrator
