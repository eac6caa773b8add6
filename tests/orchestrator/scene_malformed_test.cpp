// SPDX-License-Identifier: MIT
// Table-driven test: each malformed scene is the valid base scene with one
// edit, and must be refused with a message naming file:line:column, the
// field, the value and what is allowed.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "sadr/common/status.hpp"
#include "sadr/orchestrator/scene_loader.hpp"
#include "scene_test_support.hpp"

namespace sadr::orchestrator {
namespace {

using test::kBaseScene;
using test::replace_once;

struct MalformedCase {
  const char* name;
  std::string from;  ///< text of the base scene to replace
  std::string to;
  std::vector<std::string> expected;  ///< fragments that must all appear in the message
  std::string from2 = {};             ///< optional second edit
  std::string to2 = {};
};

std::string error_of(const std::string& text, const std::string& file = "scene.yaml") {
  try {
    (void)parse_scene(text, file);
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "<no error>";
}

/// The base scene's fluid section as an sdpd open channel with `open_boundary` (lines 13-16).
std::string open_channel(const std::string& open_boundary) {
  return "  backend: sdpd\n  sound_speed: 1\n  shear_viscosity: 0.1\n  open_boundary: " +
         open_boundary + "\n";
}

const std::vector<MalformedCase>& cases() {
  static const std::vector<MalformedCase> kCases = {
      {"misspelt_key_suggests_nearest",
       "    diffusivity: 0.1\n",
       "    diffusivty: 0.1\n",
       {"scene.yaml:17:5: unknown key 'diffusivty' in species[0]; did you mean 'diffusivity'?",
        "scene.yaml:16:5: species[0].diffusivity: missing; required: a number >= 0"}},
      {"synonym_key_suggests_our_name",
       "    diffusivity: 0.1\n",
       "    kappa: 0.1\n",
       {"scene.yaml:17:5: unknown key 'kappa' in species[0]; did you mean 'diffusivity'?"}},
      {"negative_diffusivity",
       "    diffusivity: 0.1\n",
       "    diffusivity: -0.1\n",
       {"scene.yaml:17:18: species[0].diffusivity: -0.1 is out of range; allowed: a number >= 0 "
        "[length^2/time]"}},
      {"negative_rate",
       "rate: 1.0}",
       "rate: -1.0}",
       {"scene.yaml:24:32: reactions[0].rate: -1.0 is out of range; allowed: a number >= 0 "
        "[1/time]"}},
      {"zero_smoothing_length",
       "  smoothing_length: 0.45\n",
       "  smoothing_length: 0\n",
       {"scene.yaml:14:21: fluid.smoothing_length: 0 is out of range; allowed: a number > 0 "
        "[length]"}},
      {"zero_coupling_step",
       "  coupling_step: 0.1\n",
       "  coupling_step: 0\n",
       {"scene.yaml:26:18: time.coupling_step: 0 is out of range; allowed: a number > 0"}},
      {"negative_end_time",
       "  end: 1.0\n",
       "  end: -2\n",
       {"scene.yaml:27:8: time.end: -2 is out of range; allowed: a number >= 0 [time]"}},
      {"unknown_backend_lists_known",
       "  backend: static\n",
       "  backend: sdp\n",
       {"scene.yaml:13:12: fluid.backend: unknown fluid backend 'sdp'; did you mean 'sdpd'? "
        "(allowed: prescribed, sdpd, static, tdpd)"}},
      // The backend schema decides (sadr/fluid/backend_schema.hpp): kernels, parameters.
      {"kernel_the_backend_lacks",
       "  backend: static\n",
       "  backend: tdpd\n  kernel: wendland_c2\n",
       {"scene.yaml:14:11: fluid.kernel: unknown kernel 'wendland_c2'", "(allowed: lucy)"}},
      {"parameter_unknown_to_the_backend",
       "  smoothing_length: 0.45\n",
       "  smoothing_length: 0.45\n  parameters: {gamma: 4}\n",
       {"scene.yaml:15:23: fluid.parameters.gamma: unknown parameter of backend 'static'; "
        "allowed: diffusion_eps (sadr backends)"}},
      {"parameter_out_of_the_schema_range",
       "  backend: static\n",
       "  backend: tdpd\n  parameters: {lambda: 1.5}\n",
       {"scene.yaml:14:24: fluid.parameters.lambda: 1.5 is out of range; allowed: [0, 1] "
        "[dimensionless] (Groot-Warren velocity-prediction factor)"}},
      // A schema choice is a name (prescribed.field), not its index.
      {"parameter_name_not_a_choice",
       "  backend: static\n",
       "  backend: prescribed\n  parameters: {field: rotaton}\n",
       {"scene.yaml:14:23: fluid.parameters.field: unknown name 'rotaton'; did you mean "
        "'rotation'? (allowed: uniform, shear, poiseuille, rotation, csv)"}},
      {"parameter_choice_given_as_a_number",
       "  backend: static\n",
       "  backend: prescribed\n  parameters: {field: 3}\n",
       {"fluid.parameters.field: unknown name '3'",
        "(allowed: uniform, shear, poiseuille, rotation, csv)"}},
      // The wall model is one of the backend's (schema); morris needs a plane per wall region.
      {"wall_model_the_backend_lacks",
       "  backend: static\n",
       "  backend: tdpd\n  wall_model: morris\n",
       {"fluid.wall_model: unknown wall model 'morris'", "(allowed: stationary)"}},
      {"adami_on_a_backend_without_it",
       "  backend: static\n",
       "  backend: tdpd\n  wall_model: adami\n",
       {"fluid.wall_model: unknown wall model 'adami'", "(allowed: stationary)"}},
      {"morris_without_wall_planes",
       "  backend: static\n",
       "  backend: sdpd\n  sound_speed: 1\n  shear_viscosity: 0.1\n  wall_model: morris\n",
       {"fluid.wall_planes: missing; wall_model morris needs the wall surface of each wall "
        "region"}},
      {"wall_planes_without_morris",
       "  backend: static\n",
       "  backend: static\n  wall_planes: [{region: left, point: [0], normal: [1]}]\n",
       {"fluid.wall_planes: only with wall_model: morris (the wall model here is stationary)"}},
      {"wall_plane_of_an_unknown_region",
       "  backend: static\n",
       "  backend: sdpd\n  sound_speed: 1\n  shear_viscosity: 0.1\n  wall_model: morris\n"
       "  wall_planes: [{region: lef, point: [0.1], normal: [1]}]\n",
       {"fluid.wall_planes[0].region: unknown region 'lef' (allowed: left)"}},
      {"wall_plane_normal_zero",
       "  backend: static\n",
       "  backend: sdpd\n  sound_speed: 1\n  shear_viscosity: 0.1\n  wall_model: morris\n"
       "  wall_planes: [{region: left, point: [0.1], normal: [0]}]\n",
       {"fluid.wall_planes[0].normal: must be non-zero"}},
      {"wall_circle_with_a_normal",
       "  backend: static\n",
       "  backend: sdpd\n  sound_speed: 1\n  shear_viscosity: 0.1\n  wall_model: morris\n"
       "  wall_planes: [{region: left, center: [0.1], radius: 0.1, normal: [1]}]\n",
       {"fluid.wall_planes[0].normal: not with radius"}},
      {"wall_center_without_radius",
       "  backend: static\n",
       "  backend: sdpd\n  sound_speed: 1\n  shear_viscosity: 0.1\n  wall_model: morris\n"
       "  wall_planes: [{region: left, center: [0.1], point: [0.1], normal: [1]}]\n",
       {"fluid.wall_planes[0].center: only with radius"}},
      {"wall_circle_radius_zero",
       "  backend: static\n",
       "  backend: sdpd\n  sound_speed: 1\n  shear_viscosity: 0.1\n  wall_model: morris\n"
       "  wall_planes: [{region: left, center: [0.1], radius: 0}]\n",
       {"fluid.wall_planes[0].radius:"}},
      {"species_name_reused",
       "  - name: B\n",
       "  - name: A\n",
       {"scene.yaml:20:11: species[1].name: species name 'A' is already used"}},
      {"reaction_unknown_species",
       "\"A -> 0\"",
       "\"A + Q -> 0\"",
       {"scene.yaml:24:16: reactions[0].equation: unknown species 'Q'; did you mean 'A'?",
        "(declared: A, B)"}},
      {"reaction_order_three",
       "\"A -> 0\"",
       "\"3 A -> 0\"",
       {"scene.yaml:24:16: reactions[0].equation: order 3 is not allowed; allowed: mass-action "
        "order 0, 1 or 2"}},
      {"reaction_mixes_stochastic_and_deterministic",
       "\"A -> 0\"",
       "\"A + B -> 0\"",
       {"reactions[0].equation: mixes stochastic species 'A' with deterministic species 'B'"}},
      {"reaction_without_arrow",
       "\"A -> 0\"",
       "\"A = 0\"",
       {"scene.yaml:24:16: reactions[0].equation: 'A = 0' has no arrow"}},
      {"reversible_needs_reverse_rate",
       "\"A -> 0\"",
       "\"A <-> 0\"",
       {"scene.yaml:24:5: reactions[0].reverse_rate: missing; required"}},
      {"reverse_rate_on_irreversible",
       "rate: 1.0}",
       "rate: 1.0, reverse_rate: 2}",
       {"scene.yaml:24:51: reactions[0].reverse_rate: only a reversible reaction"}},
      {"unknown_region_suggests_nearest",
       "    - {region: left, kind: wall}\n",
       "    - {region: lefft, kind: wall}\n",
       {"scene.yaml:10:16: particles.fill[0].region: unknown region 'lefft'; did you mean "
        "'left'?"}},
      {"dimension_out_of_range",
       "dimension: 1\n",
       "dimension: 4\n",
       {"scene.yaml:1:12: dimension: '4' is not allowed; allowed: a whole number in [1, 3]",
        "scene.yaml': 1 problem\n"}},  // no follow-up errors from the unusable dimension
      {"box_upper_below_lower",
       "  upper: [1.0]\n",
       "  upper: [-1.0]\n",
       {"scene.yaml:4:10: box.upper: axis 0: upper -1 must be greater than lower 0"}},
      {"box_vector_wrong_length",
       "  lower: [0.0]\n",
       "  lower: [0.0, 0.0]\n",
       {"scene.yaml:3:10: box.lower: expected a list of 1 numbers [length]", "got a list of 2"}},
      {"spacing_not_a_number",
       "  spacing: 0.25\n",
       "  spacing: abc\n",
       {"scene.yaml:8:12: particles.spacing: 'abc' is not a number; allowed: a number > 0"}},
      {"yaml_syntax_error", "  upper: [1.0]\n", "  upper: [1.0\n", {"YAML syntax error"}},
      {"invalid_species_name",
       "  - name: B\n",
       "  - name: 2B\n",
       {"scene.yaml:20:11: species[1].name: '2B' is not a valid species name"}},
      {"dirichlet_on_fluid_only_region",
       "    - {region: left, kind: wall}\n",
       "    - {region: left, kind: fluid}\n",
       {"scene.yaml:19:18: species[0].boundaries[0].region: region 'left' holds no wall, inlet "
        "or outlet particles"}},
      {"unknown_splitting_suggests_strang",
       "  end: 1.0\n",
       "  end: 1.0\n  splitting: strong\n",
       {"scene.yaml:28:14: time.splitting: unknown splitting 'strong'; did you mean 'strang'? "
        "(allowed: lie, strang)"}},
      {"output_time_after_end",
       "  end: 1.0\n",
       "  end: 1.0\noutput:\n  times: [0.5, 2.0]\n",
       {"scene.yaml:29:16: output.times[1]: 2 is after the end time 1"}},
      {"unknown_vtk_encoding_suggests_binary",
       "  end: 1.0\n",
       "  end: 1.0\noutput:\n  vtk_encoding: binray\n",
       {"scene.yaml:29:17: output.vtk_encoding: unknown VTK encoding 'binray'; did you mean "
        "'binary'? (allowed: binary, ascii)"}},
      {"missing_time_section",
       "time:\n  coupling_step: 0.1\n  end: 1.0\n",
       "",
       {"scene.yaml:1:1: time: missing; required: a map with coupling_step and end"}},
      {"unknown_top_level_key",
       "  end: 1.0\n",
       "  end: 1.0\nsead: 3\n",
       {"scene.yaml:28:1: unknown key 'sead' in the scene; did you mean 'seed'?"}},
      {"fractional_count_for_stochastic_species",
       "    diffusivity: 0.1\n",
       "    diffusivity: 0.1\n    initial: [{count: 2.5}]\n",
       {"species[0].initial[0].count: 2.5 is not allowed for the stochastic species 'A'; "
        "allowed: a whole number 0 <= n <= 2^53 = 9007199254740992"}},
      // 1e19 used to overflow on its way to the SSA's 64-bit counts and arrive as -2^63
      // (found by bench/validation/stability_map.py).
      {"copy_number_beyond_2_53",
       "    diffusivity: 0.1\n",
       "    diffusivity: 0.1\n    initial: [{count: 1.0e19}]\n",
       {"species[0].initial[0].count: 1e+19 is not allowed for the stochastic species 'A'; "
        "allowed: a whole number 0 <= n <= 2^53"}},
      {"copy_number_from_concentration_beyond_2_53",
       "    diffusivity: 0.1\n",
       "    diffusivity: 0.1\n    initial: [{concentration: 1.0e300}]\n",
       {"species[0].initial[0].concentration: 1e+300 gives",
        "of the stochastic species 'A'; "
        "allowed: a copy number C V <= 2^53"}},
      {"sdpd_needs_sound_speed",
       "  backend: static\n",
       "  backend: sdpd\n",
       {"scene.yaml:13:3: fluid.sound_speed: missing, and nothing in the scene sets a flow speed "
        "or a pressure variation to choose it from",
        "fluid.shear_viscosity: missing"}},
      {"periodic_axis_spacing_mismatch",
       "  upper: [1.0]\n",
       "  upper: [1.0]\n  periodic: [true]\n",
       {"scene.yaml:9:12: particles.spacing: 0.3 does not divide the periodic box length 1 "
        "along x"},
       "  spacing: 0.25\n",
       "  spacing: 0.3\n"},
      {"both_h_and_h_over_dx",
       "  smoothing_length: 0.45\n",
       "  smoothing_length: 0.45\n  h_over_dx: 1.8\n",
       {"scene.yaml:15:14: fluid.h_over_dx: give either smoothing_length or h_over_dx, not both"}},
      {"unknown_jump_convention",
       "  end: 1.0\n",
       "  end: 1.0\nssa: {convention: symetric}\n",
       {"scene.yaml:28:19: ssa.convention: unknown jump convention 'symetric'; did you mean "
        "'symmetric'?"}},
      {"negative_temperature",
       "  smoothing_length: 0.45\n",
       "  smoothing_length: 0.45\n  temperature: -1\n",
       {"scene.yaml:15:16: fluid.temperature: -1 is out of range; allowed: a number >= 0 "
        "[energy]"}},
      {"boussinesq_unknown_species",
       "  smoothing_length: 0.45\n",
       "  smoothing_length: 0.45\n  boussinesq: {species: C, coefficient: 1}\n",
       {"scene.yaml:15:25: fluid.boussinesq.species: unknown species 'C'"}},
      {"region_name_reused",
       "regions:\n",
       "regions:\n  - {name: left, shape: sphere, center: "
       "[0.5], radius: 0.1}\n",
       {"scene.yaml:7:12: regions[1].name: region name 'left' is already used"}},
      {"region_key_of_other_shape",
       "shape: box, lower: [0.0], upper: [0.0]}",
       "shape: box, lower: [0.0], upper: [0.0], radius: 2}",
       {"scene.yaml:6:66: regions[0].radius: key 'radius' does not apply to shape 'box'"}},
      {"negative_seed",
       "  end: 1.0\n",
       "  end: 1.0\nseed: -1\n",
       {"scene.yaml:28:7: seed: '-1' is not allowed; allowed: a whole number"}},
      {"initial_needs_count_or_concentration",
       "    diffusivity: 0.1\n",
       "    diffusivity: 0.1\n    initial: [{region: left}]\n",
       {"scene.yaml:18:15: species[0].initial[0]: give exactly one of 'count'"}},
      {"duplicate_key",
       "  end: 1.0\n",
       "  end: 1.0\n  end: 2.0\n",
       {"scene.yaml:28:3: duplicate key 'end' in time"}},
      {"negative_inflow_value_of_a_deterministic_species",
       "    diffusivity: 0.2\n",
       "    diffusivity: 0.2\n    boundaries: [{region: left, condition: inflow, value: -1}]\n",
       {"scene.yaml:23:59: species[1].boundaries[0].value: -1 is out of range; allowed: a "
        "number >= 0"}},
      {"inflow_needs_box_or_channel",
       "condition: dirichlet, value: 4}",
       "condition: inflow, value: 4}",
       {"species[0].boundaries[0].region: condition 'inflow' needs a region of shape box or "
        "channel"},
       "shape: box, lower: [0.0], upper: [0.0]}",
       "shape: sphere, center: [0.0], radius: 0.1}"},
      {"unknown_condition",
       "condition: dirichlet",
       "condition: dirichlett",
       {"species[0].boundaries[0].condition: unknown boundary condition 'dirichlett'; did you "
        "mean 'dirichlet'?"}},
      // Open boundaries (fluid.open_boundary): sdpd backend, lines 13-16; the reaction fires
      // on fluid, inlet and outlet unless a case says otherwise.
      {"open_boundary_inlet_shorter_than_h",
       "  backend: static\n",
       open_channel("{inlet: [0.2, 0.45], outlet: [0.55, 1.0], mean_velocity: 0.1}"),
       {"scene.yaml:16:",
        "fluid.open_boundary.inlet: length 0.25 is shorter than the kernel "
        "support h = 0.45; allowed: a length >= h"},
       "rate: 1.0}",
       "rate: 1.0, kinds: [fluid, inlet, outlet]}"},
      {"open_boundary_unknown_key_suggests_nearest",
       "  backend: static\n",
       open_channel("{inlet: [0, 0.45], outlet: [0.55, 1.0], mean_velocty: 0.1}"),
       {"scene.yaml:16:",
        "unknown key 'mean_velocty' in fluid.open_boundary; did you mean "
        "'mean_velocity'?",
        "fluid.open_boundary.mean_velocity: missing; required: mean_velocity or max_velocity"},
       "rate: 1.0}",
       "rate: 1.0, kinds: [fluid, inlet, outlet]}"},
      {"open_boundary_needs_sdpd",
       "  smoothing_length: 0.45\n",
       "  smoothing_length: 0.45\n  open_boundary: {inlet: [0, 0.45], outlet: [0.55, 1.0], "
       "mean_velocity: 0.1}\n",
       {"scene.yaml:15:",
        "fluid.open_boundary: backend 'static' has no open boundaries; "
        "allowed: backend sdpd"},
       "rate: 1.0}",
       "rate: 1.0, kinds: [fluid, inlet, outlet]}"},
      {"open_boundary_parabolic_in_1d",
       "  backend: static\n",
       open_channel("{inlet: [0, 0.45], outlet: [0.55, 1.0], mean_velocity: 0.1, profile: "
                    "parabolic}"),
       {"fluid.open_boundary.profile: 'parabolic' needs a cross axis; allowed in 1D: uniform"},
       "rate: 1.0}",
       "rate: 1.0, kinds: [fluid, inlet, outlet]}"},
      {"open_boundary_outlet_before_inlet",
       "  backend: static\n",
       open_channel("{inlet: [0, 0.45], outlet: [0.3, 1.0], mean_velocity: 0.1}"),
       {"fluid.open_boundary.outlet: inlet [0, 0.45], outlet [0.3, 1]; allowed: inlet = "
        "[x0 - Lb, x0], outlet = [x1, x1 + Lb'] with x0 < x1"},
       "rate: 1.0}",
       "rate: 1.0, kinds: [fluid, inlet, outlet]}"},
  };
  return kCases;
}

class MalformedScene : public ::testing::TestWithParam<std::size_t> {};

TEST_P(MalformedScene, IsRefusedWithAPreciseMessage) {
  const MalformedCase& c = cases()[GetParam()];
  std::string text = replace_once(kBaseScene, c.from, c.to);
  if (!c.from2.empty()) text = replace_once(text, c.from2, c.to2);
  const std::string message = error_of(text);
  for (const auto& fragment : c.expected) {
    EXPECT_NE(message.find(fragment), std::string::npos)
        << "case " << c.name << "\nexpected fragment: " << fragment << "\nmessage:\n"
        << message;
  }
}

INSTANTIATE_TEST_SUITE_P(Table, MalformedScene, ::testing::Range<std::size_t>(0, cases().size()),
                         [](const ::testing::TestParamInfo<std::size_t>& param) {
                           return std::string(cases()[param.param].name);
                         });

TEST(MalformedSceneTable, HasAtLeastTwentyFiveCases) {
  EXPECT_GE(cases().size(), 25U);
}

TEST(MalformedScene, BaseSceneIsValid) {
  EXPECT_EQ(error_of(kBaseScene), "<no error>");
}

TEST(MalformedScene, ReportsAllProblemsInOnePass) {
  std::string text = replace_once(kBaseScene, "    diffusivity: 0.1\n", "    diffusivity: -1\n");
  text = replace_once(text, "  coupling_step: 0.1\n", "  coupling_step: -0.1\n");
  text = replace_once(text, "  backend: static\n", "  backend: stattic\n");
  const std::string message = error_of(text);
  EXPECT_NE(message.find("3 problems"), std::string::npos) << message;
  EXPECT_NE(message.find("species[0].diffusivity: -1"), std::string::npos) << message;
  EXPECT_NE(message.find("time.coupling_step: -0.1"), std::string::npos) << message;
  EXPECT_NE(message.find("did you mean 'static'?"), std::string::npos) << message;
  // Listed in file order: line 13 (backend), 17 (diffusivity), 26 (coupling_step).
  const auto p13 = message.find("scene.yaml:13:");
  const auto p17 = message.find("scene.yaml:17:");
  const auto p26 = message.find("scene.yaml:26:");
  EXPECT_LT(p13, p17);
  EXPECT_LT(p17, p26);
  EXPECT_NE(p26, std::string::npos);
}

TEST(MalformedScene, BadParticleFileRowsAreNamedByFileAndLine) {
  const std::string text =
      "dimension: 2\n"
      "box: {lower: [0.0, 0.0], upper: [1.0, 1.0]}\n"
      "particles: {file: cloud_bad.csv}\n"
      "fluid: {backend: static, smoothing_length: 0.2}\n"
      "time: {coupling_step: 0.1, end: 1.0}\n";
  const auto scene_path = test::scene_data_dir() / "inline.yaml";
  const std::string message = error_of(text, scene_path.string());
  EXPECT_NE(message.find("cloud_bad.csv:3: particle at x = 1.5 is outside the box [0, 1]"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("cloud_bad.csv:4: column 'mass': -1 is out of range"), std::string::npos)
      << message;
  EXPECT_NE(message.find("cloud_bad.csv:5: column 'kind': unknown particle kind 'water'"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("cloud_bad.csv:6: column 'z' must be 0 in a 2D scene, got 0.3"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("inline.yaml:3:19: particles.file:"), std::string::npos) << message;
}

TEST(MalformedScene, ParticleFileWithoutKindColumn) {
  const std::string text =
      "dimension: 1\n"
      "box: {lower: [0.0], upper: [1.0]}\n"
      "particles: {file: cloud_no_kind.csv}\n"
      "fluid: {backend: static, smoothing_length: 0.2}\n"
      "time: {coupling_step: 0.1, end: 1.0}\n";
  const std::string message = error_of(text, (test::scene_data_dir() / "x.yaml").string());
  EXPECT_NE(message.find("cloud_no_kind.csv:1: missing column 'kind'"), std::string::npos)
      << message;
  EXPECT_NE(message.find(": 1 problem\n"), std::string::npos) << message;
}

TEST(MalformedScene, MissingParticleFileIsNamed) {
  const std::string text =
      "dimension: 1\n"
      "box: {lower: [0.0], upper: [1.0]}\n"
      "particles: {file: nowhere.csv}\n"
      "fluid: {backend: static, smoothing_length: 0.2}\n"
      "time: {coupling_step: 0.1, end: 1.0}\n";
  const std::string message = error_of(text, (test::scene_data_dir() / "x.yaml").string());
  EXPECT_NE(message.find("cannot open particle file"), std::string::npos) << message;
  EXPECT_NE(message.find("nowhere.csv"), std::string::npos) << message;
}

TEST(MalformedScene, MissingFileIsAnInvalidArgument) {
  EXPECT_THROW((void)load_scene("/nonexistent/scene.yaml"), InvalidArgument);
}

}  // namespace
}  // namespace sadr::orchestrator
