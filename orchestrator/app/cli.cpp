// SPDX-License-Identifier: MIT
#include "cli.hpp"

#include <cmath>
#include <cstdlib>

#include "sadr/common/log.hpp"

namespace sadr::orchestrator {

CLI::Validator finite_range(double lo, double hi, const std::string& what) {
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (text.empty() || *end != '\0' || !std::isfinite(v) || v < lo || v > hi) {
          return "'" + text.substr(0, 32) + "' is out of range; allowed: " + what;
        }
        return {};
      },
      what);
}

void add_set_option(CLI::App* cmd, std::vector<std::string>& overrides) {
  cmd->add_option("--set", overrides,
                  "override a scene value before validation, PATH=VALUE (repeatable): "
                  "fluid.sound_speed=20, reactions[annihilation].rate=0.2, "
                  "species[0].diffusivity=0.1 (docs/cli.md)");
}

void apply_log_level(bool quiet, std::string level) {
  if (quiet && level == "info") level = "warn";
  if (level == "error") log::set_level(log::Level::kError);
  if (level == "warn") log::set_level(log::Level::kWarn);
  if (level == "debug") log::set_level(log::Level::kDebug);
}

}  // namespace sadr::orchestrator
