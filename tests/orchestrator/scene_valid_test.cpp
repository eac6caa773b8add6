// SPDX-License-Identifier: MIT
// Valid scenes parse to the expected particles, regions, initial values,
// chemistry and output times; every example in examples/ validates.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "sadr/common/status.hpp"
#include "sadr/orchestrator/hash.hpp"
#include "sadr/orchestrator/reaction_equation.hpp"
#include "sadr/orchestrator/scene_loader.hpp"
#include "sadr/orchestrator/scene_summary.hpp"
#include "scene_test_support.hpp"

namespace sadr::orchestrator {
namespace {

using test::kBaseScene;
using test::replace_once;

TEST(SceneValid, BaseSceneParticlesAndRegions) {
  const Scene s = parse_scene(kBaseScene, "scene.yaml");
  // Walled axis [0, 1] with dx = 0.25: points 0, 0.25, 0.5, 0.75, 1.
  ASSERT_EQ(s.particles.size(), 5U);
  EXPECT_EQ(s.box.dimension, 1);
  EXPECT_DOUBLE_EQ(s.lattice_spacing, 0.25);
  EXPECT_EQ(s.particles.kind(0), ParticleKind::kWall);
  for (std::size_t i = 1; i < 5; ++i) EXPECT_EQ(s.particles.kind(i), ParticleKind::kFluid);
  EXPECT_DOUBLE_EQ(s.particles.positions[3 * 4], 1.0);
  EXPECT_DOUBLE_EQ(s.particles.masses[0], 0.25);  // rho dx
  ASSERT_EQ(s.regions.size(), 1U);
  EXPECT_EQ(s.regions[0].particles, std::vector<std::uint32_t>{0});
  EXPECT_EQ(s.particles.ids, (std::vector<std::uint64_t>{0, 1, 2, 3, 4}));
  EXPECT_DOUBLE_EQ(s.fluid.smoothing_length, 0.45);
  EXPECT_EQ(s.fluid.backend, "static");
  EXPECT_EQ(s.seed, 0U);
  EXPECT_EQ(s.source_hash, content_hash(kBaseScene));
}

TEST(SceneValid, SummaryDescribesTheScene) {
  const auto lines = describe_scene(parse_scene(kBaseScene, "scene.yaml"));
  ASSERT_GE(lines.size(), 7U);
  EXPECT_EQ(lines[0], "domain: 1D box [0, 1] walled");
  EXPECT_EQ(lines[1], "particles: 5 (4 fluid, 1 wall), dx = 0.25, h = 0.45");
  EXPECT_EQ(lines[2], "region left: box, 1 particles");
  EXPECT_EQ(lines[6], "reaction reaction0: A -> 0, k = 1 (ssa)");
  EXPECT_EQ(lines.back(), "output: 2 frame(s)");
}

TEST(SceneValid, DirichletValueSetsInitialCountsOfWallParticles) {
  const Scene s = parse_scene(kBaseScene, "scene.yaml");
  const Species* a = s.find_species("A");
  ASSERT_NE(a, nullptr);
  EXPECT_TRUE(a->stochastic);
  ASSERT_EQ(a->boundaries.size(), 1U);
  EXPECT_EQ(a->boundaries[0].condition, BoundaryCondition::kDirichlet);
  EXPECT_DOUBLE_EQ(a->boundaries[0].value, 4.0);
  // Concentration 4 in a voxel of volume 0.25: 1 molecule.
  EXPECT_EQ(a->initial, (std::vector<double>{1, 0, 0, 0, 0}));
  const Species* b = s.find_species("B");
  ASSERT_NE(b, nullptr);
  EXPECT_FALSE(b->stochastic);
  EXPECT_EQ(s.stochastic_species_count(), 1U);
  EXPECT_EQ(s.deterministic_species_count(), 1U);
}

// fluid.kernel takes the backend's kernels (its schema entry); the default is its first.
TEST(SceneValid, KernelFromTheBackendsSchema) {
  EXPECT_EQ(parse_scene(test::kBaseScene, "scene.yaml").fluid.kernel, "lucy");
  const std::string text = test::replace_once(test::kBaseScene, "  smoothing_length: 0.45\n",
                                              "  smoothing_length: 0.45\n  kernel: wendland_c2\n");
  EXPECT_EQ(parse_scene(text, "scene.yaml").fluid.kernel, "wendland_c2");
}

// A schema choice is written as its name and sent as its index (prescribed: field, integrator).
TEST(SceneValid, ParameterNamesBecomeTheirIndex) {
  const std::string text = test::replace_once(
      test::kBaseScene, "  backend: static\n",
      "  backend: prescribed\n  parameters: {field: rotation, integrator: rk4, omega: 2}\n");
  const auto p = parse_scene(text, "scene.yaml").fluid.parameters;
  EXPECT_EQ(p.at("field"), 3.0);
  EXPECT_EQ(p.at("integrator"), 1.0);
  EXPECT_EQ(p.at("omega"), 2.0);
}

// fluid.wall_model: the backend's first wall model by default; morris with its planes (the
// normal normalised).
TEST(SceneValid, WallModelAndPlanes) {
  EXPECT_EQ(parse_scene(test::kBaseScene, "scene.yaml").fluid.wall_model, "stationary");
  const std::string text = test::replace_once(
      test::kBaseScene, "  backend: static\n",
      "  backend: sdpd\n  sound_speed: 1\n  shear_viscosity: 0.1\n  wall_model: morris\n"
      "  wall_planes: [{region: left, point: [0.1], normal: [2]}]\n");
  const auto fl = parse_scene(text, "scene.yaml").fluid;
  EXPECT_EQ(fl.wall_model, "morris");
  ASSERT_EQ(fl.wall_planes.size(), 1U);
  EXPECT_EQ(fl.wall_planes[0].region, "left");
  EXPECT_EQ(fl.wall_planes[0].point[0], 0.1);
  EXPECT_EQ(fl.wall_planes[0].normal[0], 1.0);
  EXPECT_EQ(fl.wall_planes[0].radius, 0.0);
  // a curved surface: a circle (sphere) around center, the fluid outside
  const auto curved =
      parse_scene(test::replace_once(text, "{region: left, point: [0.1], normal: [2]}",
                                     "{region: left, center: [0.3], radius: 0.2}"),
                  "scene.yaml")
          .fluid;
  ASSERT_EQ(curved.wall_planes.size(), 1U);
  EXPECT_EQ(curved.wall_planes[0].point[0], 0.3);
  EXPECT_EQ(curved.wall_planes[0].radius, 0.2);
}

TEST(SceneValid, OutputTimesDefaultToStartAndEnd) {
  const Scene s = parse_scene(kBaseScene, "scene.yaml");
  EXPECT_EQ(s.output.times, (std::vector<double>{0.0, 1.0}));
  EXPECT_EQ(s.output.species, (std::vector<std::string>{"A", "B"}));
  EXPECT_EQ(s.time.splitting, Splitting::kLie);
}

TEST(SceneValid, VtkEncodingDefaultsToBinaryAndTakesAscii) {
  EXPECT_EQ(parse_scene(kBaseScene, "scene.yaml").output.vtk_encoding, VtkEncoding::kBinary);
  const std::string text =
      replace_once(kBaseScene, "  end: 1.0\n", "  end: 1.0\noutput: {vtk_encoding: ascii}\n");
  EXPECT_EQ(parse_scene(text, "scene.yaml").output.vtk_encoding, VtkEncoding::kAscii);
}

TEST(SceneValid, OutputEveryIsExactMultiplesAndEnd) {
  const std::string text = replace_once(
      kBaseScene, "  end: 1.0\n", "  end: 1.0\noutput: {every: 0.3, include_initial: false}\n");
  const Scene s = parse_scene(text, "scene.yaml");
  ASSERT_EQ(s.output.times.size(), 4U);
  EXPECT_EQ(s.output.times[0], 0.3);
  EXPECT_EQ(s.output.times[1], 2 * 0.3);
  EXPECT_EQ(s.output.times[2], 3 * 0.3);
  EXPECT_EQ(s.output.times[3], 1.0);
}

TEST(SceneValid, OutputEveryMergesRoundOffDuplicateOfEnd) {
  // 10 * 0.1 = 1.0000000000000002 would otherwise be a second frame next to 1.0.
  const std::string text =
      replace_once(kBaseScene, "  end: 1.0\n", "  end: 1.0\noutput: {every: 0.1}\n");
  const Scene s = parse_scene(text, "scene.yaml");
  ASSERT_EQ(s.output.times.size(), 11U);
  EXPECT_EQ(s.output.times.front(), 0.0);
  EXPECT_EQ(s.output.times.back(), 1.0);
}

TEST(SceneValid, ReversibleReactionBecomesTwo) {
  const std::string text =
      replace_once(kBaseScene, "  - {equation: \"A -> 0\", rate: 1.0}\n",
                   "  - {name: bind, equation: \"2 A <-> C\", rate: 1.5, reverse_rate: 0.5,\n"
                   "     regions: [left], kinds: [wall, fluid]}\n");
  const std::string with_c =
      replace_once(text, "  - name: B\n", "  - {name: C, diffusivity: 0}\n  - name: B\n");
  const Scene s = parse_scene(with_c, "scene.yaml");
  ASSERT_EQ(s.reactions.size(), 2U);
  EXPECT_EQ(s.reactions[0].name, "bind");
  EXPECT_EQ(s.reactions[0].reactants, (std::vector<StoichiometryEntry>{{"A", 2}}));
  EXPECT_EQ(s.reactions[0].products, (std::vector<StoichiometryEntry>{{"C", 1}}));
  EXPECT_EQ(s.reactions[0].order(), 2U);
  EXPECT_DOUBLE_EQ(s.reactions[0].rate, 1.5);
  EXPECT_EQ(s.reactions[1].name, "bind_reverse");
  EXPECT_EQ(s.reactions[1].reactants, (std::vector<StoichiometryEntry>{{"C", 1}}));
  EXPECT_DOUBLE_EQ(s.reactions[1].rate, 0.5);
  EXPECT_EQ(s.reactions[1].regions, std::vector<std::string>{"left"});
  EXPECT_EQ(s.reactions[1].kinds,
            (std::vector<ParticleKind>{ParticleKind::kWall, ParticleKind::kFluid}));
  EXPECT_TRUE(s.reactions[0].stochastic);
}

TEST(SceneValid, DefaultReactionKindsAreFluid) {
  const Scene s = parse_scene(kBaseScene, "scene.yaml");
  ASSERT_EQ(s.reactions.size(), 1U);
  EXPECT_EQ(s.reactions[0].kinds, std::vector<ParticleKind>{ParticleKind::kFluid});
  EXPECT_TRUE(s.reactions[0].regions.empty());
}

TEST(SceneValid, ReactionEquationGrammar) {
  auto eq = parse_reaction_equation("A + A -> 0");
  EXPECT_EQ(eq.reactants, (std::vector<StoichiometryEntry>{{"A", 2}}));
  EXPECT_TRUE(eq.products.empty());
  eq = parse_reaction_equation("0 -> X_1");
  EXPECT_TRUE(eq.reactants.empty());
  EXPECT_EQ(eq.products, (std::vector<StoichiometryEntry>{{"X_1", 1}}));
  eq = parse_reaction_equation("R+L<->RL");
  EXPECT_TRUE(eq.reversible);
  EXPECT_EQ(eq.reactants, (std::vector<StoichiometryEntry>{{"R", 1}, {"L", 1}}));
  eq = parse_reaction_equation("2B ->");
  EXPECT_EQ(eq.reactants, (std::vector<StoichiometryEntry>{{"B", 2}}));
  EXPECT_THROW(parse_reaction_equation("A + -> B"), InvalidArgument);
  EXPECT_THROW(parse_reaction_equation("A -> B -> C"), InvalidArgument);
  EXPECT_THROW(parse_reaction_equation("0 -> 0"), InvalidArgument);
}

TEST(SceneValid, PeriodicLatticeUsesCellCentres2D) {
  const std::string text =
      "dimension: 2\n"
      "box: {lower: [0, 0], upper: [1, 0.5], periodic: [true, true]}\n"
      "regions:\n"
      "  - {name: disk, shape: disk, center: [0.5, 0.25], radius: 0.2}\n"
      "  - {name: ring, shape: annulus, center: [0.5, 0.25], inner_radius: 0.1, "
      "outer_radius: 0.2}\n"
      "  - {name: band, shape: channel, axis: y, lower: 0.0, upper: 0.1}\n"
      "particles: {spacing: 0.1, density: 2.0}\n"
      "fluid: {backend: static, h_over_dx: 2}\n"
      "time: {coupling_step: 0.1, end: 0}\n";
  const Scene s = parse_scene(text, "p.yaml");
  ASSERT_EQ(s.particles.size(), 50U);  // 10 x 5 cell centres
  EXPECT_DOUBLE_EQ(s.particles.positions[0], 0.05);
  EXPECT_DOUBLE_EQ(s.particles.positions[1], 0.05);
  EXPECT_DOUBLE_EQ(s.particles.masses[0], 2.0 * 0.01);
  EXPECT_DOUBLE_EQ(s.fluid.smoothing_length, 0.2);
  // Brute-force membership for comparison.
  auto count_if = [&](auto pred) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < s.particles.size(); ++i) {
      const double x = s.particles.positions[3 * i] - 0.5;
      const double y = s.particles.positions[3 * i + 1] - 0.25;
      n += pred(std::sqrt(x * x + y * y), s.particles.positions[3 * i + 1]) ? 1 : 0;
    }
    return n;
  };
  EXPECT_EQ(s.find_region("disk")->particles.size(),
            count_if([](double r, double) { return r <= 0.2 + 1e-12; }));
  EXPECT_EQ(s.find_region("ring")->particles.size(),
            count_if([](double r, double) { return r >= 0.1 - 1e-12 && r <= 0.2 + 1e-12; }));
  EXPECT_EQ(s.find_region("band")->particles.size(), 10U);  // the row y = 0.05
  EXPECT_EQ(s.output.times, std::vector<double>{0.0});
}

TEST(SceneValid, ParticlesFromCsvFile) {
  const std::string text =
      "dimension: 2\n"
      "box: {lower: [0.0, 0.0], upper: [1.0, 1.0]}\n"
      "regions: [{name: walls, shape: box, lower: [0, 0], upper: [1, 1], "
      "kinds: [wall]}]\n"
      "particles: {file: cloud_2d.csv}\n"
      "fluid: {backend: static, smoothing_length: 0.2}\n"
      "time: {coupling_step: 0.1, end: 1.0}\n";
  const Scene s = parse_scene(text, test::scene_data_dir() / "inline.yaml");
  ASSERT_EQ(s.particles.size(), 5U);
  EXPECT_EQ(s.particles.kind(0), ParticleKind::kWall);
  EXPECT_EQ(s.particles.kind(4), ParticleKind::kFluid);
  EXPECT_DOUBLE_EQ(s.particles.positions[3 * 4], 0.05);
  EXPECT_DOUBLE_EQ(s.particles.masses[2], 0.01);
  EXPECT_EQ(s.find_region("walls")->particles, (std::vector<std::uint32_t>{0, 1}));
  EXPECT_EQ(s.lattice_spacing, 0.0);
  // The particle file is part of the scene's identity.
  EXPECT_NE(s.source_hash, content_hash(text));
  EXPECT_EQ(s.source_hash,
            content_hash(text + read_file_bytes(test::scene_data_dir() / "cloud_2d.csv")));
}

TEST(SceneValid, InflowBufferOnFluidParticlesOfABox) {
  // A box over fluid particles is fine for 'inflow' (it is geometric); a count
  // becomes the concentration count / V.
  const std::string text = test::replace_once(
      test::replace_once(kBaseScene, "  - {name: left, shape: box, lower: [0.0], upper: [0.0]}\n",
                         "  - {name: left, shape: box, lower: [0.0], upper: [0.0]}\n"
                         "  - {name: inlet, shape: box, lower: [0.2], upper: [0.3]}\n"),
      "      - {region: left, condition: dirichlet, value: 4}\n",
      "      - {region: left, condition: dirichlet, value: 4}\n"
      "      - {region: inlet, condition: inflow, count: 5}\n");
  const Scene s = parse_scene(text, "scene.yaml");
  const Species* a = s.find_species("A");
  ASSERT_EQ(a->boundaries.size(), 2U);
  EXPECT_EQ(a->boundaries[1].condition, BoundaryCondition::kInflow);
  EXPECT_EQ(a->boundaries[1].region, "inlet");
  EXPECT_DOUBLE_EQ(a->boundaries[1].value, 5.0 / 0.25);  // V = dx = 0.25 in 1D
}

std::filesystem::path examples_dir() {
  return std::filesystem::path(SADR_SOURCE_DIR) / "examples";
}

TEST(Examples, EveryExampleValidates) {
  std::size_t n = 0;
  for (const auto& entry : std::filesystem::directory_iterator(examples_dir())) {
    if (entry.path().extension() != ".yaml") continue;
    ++n;
    EXPECT_NO_THROW({
      try {
        const Scene s = load_scene(entry.path());
        EXPECT_GT(s.particles.size(), 0U) << entry.path();
        std::ifstream in(entry.path());
        const std::string text((std::istreambuf_iterator<char>(in)), {});
        // The hash also covers a particle file or the mesh files a geometry reads.
        if (text.find("type: mesh") != std::string::npos) {
          EXPECT_NE(s.source_hash, file_hash(entry.path())) << entry.path();
        } else if (s.lattice_spacing > 0) {
          EXPECT_EQ(s.source_hash, file_hash(entry.path())) << entry.path();
        }
      } catch (const std::exception& e) {
        ADD_FAILURE() << e.what();
        throw;
      }
    }) << entry.path();
  }
  EXPECT_GE(n, 5U);
}

TEST(Examples, AnnihilationMatchesRefsSection4) {
  for (const auto& [file, np] : std::vector<std::pair<std::string, std::size_t>>{
           {"annihilation_1d_stochastic.yaml", 17},
           {"annihilation_1d_stochastic_n33.yaml", 33},
           {"annihilation_1d_stochastic_n65.yaml", 65},
           {"annihilation_1d_deterministic.yaml", 17}}) {
    const Scene s = load_scene(examples_dir() / file);
    ASSERT_EQ(s.particles.size(), np) << file;
    const double dx = 1.0 / static_cast<double>(np - 1);
    EXPECT_DOUBLE_EQ(s.lattice_spacing, dx);
    EXPECT_NEAR(s.fluid.smoothing_length, 1.8 * dx, 1e-15);
    EXPECT_EQ(s.particles.kind(0), ParticleKind::kWall);
    EXPECT_EQ(s.particles.kind(np - 1), ParticleKind::kWall);
    const Species* a = s.find_species("A");
    ASSERT_NE(a, nullptr);
    EXPECT_DOUBLE_EQ(a->diffusivity, 0.1);
    // C0 = N_b (Np - 1) / L with N_b = 1e3 molecules per boundary particle.
    EXPECT_NEAR(a->boundaries[0].value, 1000.0 * static_cast<double>(np - 1), 1e-9);
    EXPECT_NEAR(a->initial[0], a->stochastic ? 1000.0 : 1000.0 * static_cast<double>(np - 1), 1e-9);
    ASSERT_EQ(s.reactions.size(), 1U);
    EXPECT_DOUBLE_EQ(s.reactions[0].rate, 0.1);
    EXPECT_EQ(s.reactions[0].order(), 2U);
  }
}

TEST(Examples, YeastCellParametersFromTables3And4) {
  const Scene s = load_scene(examples_dir() / "yeast_cell_channel.yaml");
  // Table 3 gives Pe = x0 v0 / kappa_L = 72.05; Table 4 rounds it to 72.06,
  // which the example uses (kappa = 1 / Pe in units of x0 v0).
  const double pe = 1e-4 * 2.5e-4 / 347e-12;
  EXPECT_NEAR(pe, 72.06, 0.02);
  EXPECT_NEAR(s.find_species("L")->diffusivity, 1.0 / 72.06, 1e-6);
  EXPECT_DOUBLE_EQ(s.fluid.shear_viscosity, 1.0 / 0.025);  // 1 / Re
  const Region* membrane = s.find_region("cell_membrane");
  ASSERT_NE(membrane, nullptr);
  EXPECT_EQ(membrane->particles.size(), 6U);  // the ring; the interior particle is not in it
  for (const auto i : membrane->particles) EXPECT_EQ(s.particles.kind(i), ParticleKind::kWall);
  std::size_t fluid = 0;
  for (std::size_t i = 0; i < s.particles.size(); ++i) {
    fluid += s.particles.kind(i) == ParticleKind::kFluid ? 1 : 0;
  }
  EXPECT_EQ(fluid, 1246U);  // the paper's 1250 lattice particles minus the 4 the cell replaces
  // The inlet: 1600 molecules per particle of volume dx^2 = 0.0016 (1e6 per unit area).
  const Species* l = s.find_species("L");
  ASSERT_EQ(l->boundaries.size(), 3U);
  EXPECT_EQ(l->boundaries[0].condition, BoundaryCondition::kInflow);
  EXPECT_NEAR(l->boundaries[0].value, 1e6, 1e-6);
  EXPECT_EQ(l->boundaries[1].value, 0.0);
  ASSERT_EQ(s.reactions.size(), 2U);
  EXPECT_EQ(s.reactions[1].name, "binding_reverse");
  EXPECT_DOUBLE_EQ(s.reactions[0].rate * 1e6, 0.4);  // Da_I / Pe per unit concentration
}

}  // namespace
}  // namespace sadr::orchestrator
