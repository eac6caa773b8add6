// SPDX-License-Identifier: MIT
#include "sadr/fluid/backend_schema.hpp"

#include <cmath>
#include <cstdio>

namespace sadr::fluid::schema {

namespace {
std::string num(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char b[32];
  std::snprintf(b, sizeof b, "%.10g", v);
  return b;
}
std::string join(const std::vector<std::string>& v);
std::string range(const Parameter& p) {
  if (p.file) return "a file (path relative to the scene file)";
  if (!p.choices.empty()) return "one of " + join(p.choices);
  const bool lo = std::isfinite(p.min), hi = std::isfinite(p.max);
  std::string r = p.whole ? "a whole number, " : "";
  if (lo && hi) {
    r.append(p.open_interval ? "(" : "[").append(num(p.min)).append(", ").append(num(p.max));
    r.append(p.open_interval ? ")" : "]");
  } else if (lo) {
    r.append(p.open_interval ? "> " : ">= ").append(num(p.min));
  } else if (hi) {
    r.append(p.open_interval ? "< " : "<= ").append(num(p.max));
  } else {
    r.append("any finite number");
  }
  return r;
}
std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s.empty() ? "-" : s;
}
std::string yes(bool b) {
  return b ? "yes" : "no";
}
}  // namespace

bool Parameter::allows(double v, std::string& why) const {
  const bool inside = open_interval ? v > min && v < max : v >= min && v <= max;
  const bool ok = std::isfinite(v) && inside && (!whole || v == std::floor(v));
  if (!ok) why = range(*this);
  return ok;
}

int Parameter::choice_index(std::string_view n) const {
  for (std::size_t k = 0; k < choices.size(); ++k) {
    if (choices[k] == n) return static_cast<int>(k);
  }
  return -1;
}

/// The default as the scene writes it (a name for a choice).
static std::string default_text(const Parameter& p) {
  if (p.file) return "none";
  const auto k = static_cast<std::size_t>(p.default_value);
  return p.choices.empty() || k >= p.choices.size() ? num(p.default_value) : p.choices[k];
}

const Parameter* Backend::parameter(std::string_view n) const {
  for (const auto& p : parameters) {
    if (p.name == n) return &p;
  }
  return nullptr;
}

bool Backend::needs(std::string_view key) const {
  for (const auto& r : required) {
    if (r == key) return true;
  }
  return false;
}

const Backend* find(std::string_view name) {
  for (const auto& b : backends()) {
    if (b.name == name) return &b;
  }
  return nullptr;
}

std::string names() {
  std::vector<std::string> v;
  for (const auto& b : backends()) v.push_back(b.name);
  return join(v);
}

std::string markdown_parameters(const Backend& b) {
  std::string s = "| parameter | unit | default | allowed | meaning |\n|---|---|---|---|---|\n";
  for (const auto& p : b.parameters) {
    s += "| `" + p.name + "` | " + p.unit + " | " + default_text(p) + " | " + range(p) + " | " +
         p.doc + " |\n";
  }
  if (b.parameters.empty()) s += "| (none) | | | | |\n";
  return s;
}

/// The required keys; sound_speed is chosen from the scene when left out.
std::string required_text(const Backend& b) {
  std::string s = join(b.required);
  const std::string key = "sound_speed";
  if (const auto at = s.find(key); at != std::string::npos) {
    s.insert(at + key.size(), " (chosen when left out)");
  }
  return s;
}

std::string markdown_capabilities() {
  std::string s =
      "| backend | moves particles | transports species | thermal noise | open boundaries | "
      "wall species terms | boundary fluxes | wall models | kernels | requires |\n"
      "|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& b : backends()) {
    const auto& c = b.capabilities;
    s += "| `" + b.name + "` | " + yes(c.moves_particles) + " | " + yes(c.transports_species) +
         " | " + yes(c.thermal_noise) + " | " + yes(c.open_boundaries) + " | " +
         yes(c.wall_species_terms) + " | " + yes(c.boundary_fluxes) + " | " + join(c.wall_models) +
         " | " + join(c.kernels) + " | " + required_text(b) + " |\n";
  }
  return s;
}

std::string describe() {
  std::string s;
  for (const auto& b : backends()) {
    const auto& c = b.capabilities;
    s += b.name + ": " + b.summary + "\n";
    s += "  moves particles: " + yes(c.moves_particles) +
         ", transports species: " + yes(c.transports_species) +
         ", thermal noise: " + yes(c.thermal_noise) +
         ", open boundaries: " + yes(c.open_boundaries) +
         ", wall species terms: " + yes(c.wall_species_terms) +
         ", boundary fluxes: " + yes(c.boundary_fluxes) + "\n";
    s += "  wall models: " + join(c.wall_models) + "; kernels: " + join(c.kernels) +
         "; requires: " + required_text(b) + "\n";
    s += "  parameters (fluid.parameters):" + std::string(b.parameters.empty() ? " none\n" : "\n");
    for (const auto& p : b.parameters) {
      s += "    " + p.name + " [" + p.unit + "] default " + default_text(p) + ", " + range(p) +
           ": " + p.doc + "\n";
    }
  }
  return s;
}

}  // namespace sadr::fluid::schema
