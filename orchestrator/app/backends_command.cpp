// SPDX-License-Identifier: MIT
// `sadr backends`: every fluid backend with its capabilities and parameters, from the backend
// schema (sadr/fluid/backend_schema.hpp), the same data the scene loader validates against.
#include <cstdio>
#include <memory>

#include "cli.hpp"
#include "commands.hpp"
#include "sadr/fluid/backend_schema.hpp"

namespace sadr::orchestrator {
namespace {

int cmd_backends(bool markdown) {
  namespace schema = sadr::fluid::schema;
  std::string text;
  if (markdown) {
    text = schema::markdown_capabilities();
    for (const auto& b : schema::backends())
      text += "\n`" + b.name + "` parameters:\n\n" + schema::markdown_parameters(b);
  } else {
    text = schema::describe();
  }
  std::fputs(text.c_str(), stdout);
  return kExitOk;
}

}  // namespace

Subcommand add_backends_command(CLI::App& app) {
  auto markdown = std::make_shared<bool>(false);
  auto* backends = app.add_subcommand(
      "backends", "list the fluid backends, their capabilities and parameters (fluid.parameters)");
  backends->add_flag("--markdown", *markdown, "as the Markdown tables of docs/scene-format.md");

  return {backends, [markdown] { return cmd_backends(*markdown); }};
}

}  // namespace sadr::orchestrator
