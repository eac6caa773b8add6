// SPDX-License-Identifier: MIT
// `sadr backends`: every fluid backend with its capabilities and parameters, from the backend
// schema (sadr/fluid/backend_schema.hpp), the same data the scene loader validates against.
#include <cstdio>

#include "commands.hpp"
#include "sadr/fluid/backend_schema.hpp"

namespace sadr::orchestrator {

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

}  // namespace sadr::orchestrator
