// SPDX-License-Identifier: MIT
// `sadr validate SCENE`: parse and check a scene, print its plan and work
// estimate; exit 0 if valid, 1 if not.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <thread>

#include "cli.hpp"
#include "commands.hpp"
#include "sadr/common/log.hpp"
#include "sadr/orchestrator/scene_loader.hpp"
#include "sadr/orchestrator/scene_override.hpp"

namespace sadr::orchestrator {
namespace fs = std::filesystem;
namespace {

struct ValidateCommandOptions {
  std::string scene;
  std::vector<std::string> overrides;  ///< --set PATH=VALUE
  bool strict = false;                 ///< --strict: a scene warning is an error
};

int cmd_validate(const ValidateCommandOptions& o) {
  try {
    const Scene scene = load_scene(o.scene, parse_overrides(o.overrides));
    if (o.strict && !scene.warnings.empty()) {
      for (const auto& w : scene.warnings) log::warn(w);
      std::fprintf(stderr, "%s: refused by --strict: %zu warning(s)\n", o.scene.c_str(),
                   scene.warnings.size());
      return kExitInvalidInput;
    }
    Plan plan = make_plan(scene);
    const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
    decide_overlap(plan, OverlapRequest::kAuto, hw, fluid_threads(ServiceOptions{}, hw), 1);
    print_plan(scene, plan, ServiceOptions{});
    const fs::path out =
        scene.output.directory.empty() ? fs::path(".") : fs::path(scene.output.directory);
    const WorkEstimate e = estimate_with_backend(scene, plan, out, 1, 1);
    for (const auto& line : e.lines()) std::fprintf(stderr, "  - %s\n", line.c_str());
    for (const auto& note : e.notes) log::warn(note);
    enforce_limits(e, true);
    for (const auto& line : e.soft) {
      std::fprintf(stderr, "%s: warning: %s; sadr run refuses it without --allow-large\n",
                   o.scene.c_str(), line.c_str());
    }
    std::printf("%s: valid\n", o.scene.c_str());
    return kExitOk;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return kExitInvalidInput;
  }
}

}  // namespace

Subcommand add_validate_command(CLI::App& app) {
  auto o = std::make_shared<ValidateCommandOptions>();
  auto* validate =
      app.add_subcommand("validate", "parse and check a scene; exit 0 if valid, 1 if not");
  validate->add_option("scene", o->scene, "scene file (YAML)")
      ->required()
      ->check(CLI::ExistingFile);
  add_set_option(validate, o->overrides);
  validate->add_flag("--strict", o->strict,
                     "refuse the scene (exit 1) when it has warnings: a reaction, initial value, "
                     "boundary or observable that selects no particle, molecules that never "
                     "reach the fluid");

  return {validate, [o] { return cmd_validate(*o); }};
}

}  // namespace sadr::orchestrator
