// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/scene_summary.hpp"

#include <array>

#include "sadr/fluid/backend_schema.hpp"
#include "sadr/orchestrator/diagnostics.hpp"

namespace sadr::orchestrator {

namespace {
std::string side(const std::vector<StoichiometryEntry>& entries) {
  if (entries.empty()) return "0";
  std::string s;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    if (i) s += " + ";
    if (entries[i].count > 1) s += std::to_string(entries[i].count) + " ";
    s += entries[i].species;
  }
  return s;
}
}  // namespace

std::vector<std::string> describe_scene(const Scene& s) {
  std::vector<std::string> out;
  std::string box = "domain: " + std::to_string(s.box.dimension) + "D box";
  for (int a = 0; a < s.box.dimension; ++a) {
    const auto ua = static_cast<std::size_t>(a);
    box += std::string(a ? " x " : " ") + "[" + format_number(s.box.lo[ua]) + ", " +
           format_number(s.box.hi[ua]) + "]" + (s.box.periodic[ua] ? " periodic" : " walled");
  }
  out.push_back(box);
  std::array<std::size_t, 4> kinds{};
  for (std::size_t i = 0; i < s.particles.size(); ++i) {
    ++kinds[static_cast<std::size_t>(s.particles.kind(i))];
  }
  std::string parts = "particles: " + std::to_string(s.particles.size()) + " (";
  bool first = true;
  for (std::size_t k = 0; k < kinds.size(); ++k) {
    if (kinds[k] == 0) continue;
    parts += (first ? "" : ", ") + std::to_string(kinds[k]) + " " +
             std::string(to_string(static_cast<ParticleKind>(k)));
    first = false;
  }
  parts += ")";
  if (s.lattice_spacing > 0) parts += ", dx = " + format_number(s.lattice_spacing);
  parts += ", h = " + format_number(s.fluid.smoothing_length);
  out.push_back(parts);
  for (const auto& r : s.regions) {
    out.push_back("region " + r.name + ": " + std::string(to_string(r.shape)) + ", " +
                  std::to_string(r.particles.size()) + " particles");
  }
  const auto* backend = sadr::fluid::schema::find(s.fluid.backend);  // c0, eta if it needs them
  const bool sph = backend && backend->needs("sound_speed");         // chosen when left out
  out.push_back("fluid: " + s.fluid.backend +
                ", rho0 = " + format_number(s.fluid.reference_density) +
                (sph ? ", c0 = " + format_number(s.fluid.sound_speed) +
                           ", eta = " + format_number(s.fluid.shear_viscosity)
                     : std::string()) +
                ", kT = " + format_number(s.fluid.temperature));
  for (const auto& sp : s.species) {
    out.push_back("species " + sp.name + ": " + (sp.stochastic ? "stochastic" : "deterministic") +
                  ", kappa = " + format_number(sp.diffusivity) + ", " +
                  std::to_string(sp.boundaries.size()) + " boundary condition(s)");
  }
  for (const auto& r : s.reactions) {
    out.push_back("reaction " + r.name + ": " + side(r.reactants) + " -> " + side(r.products) +
                  ", k = " + format_number(r.rate) + (r.stochastic ? " (ssa)" : " (fluid)"));
  }
  out.push_back("time: tau = " + format_number(s.time.coupling_step) + ", end = " +
                format_number(s.time.end) + ", " + std::string(to_string(s.time.splitting)) +
                " splitting, seed " + std::to_string(s.seed));
  if (const auto& tol = s.time.tolerance) {
    out.push_back("time.tolerance: relative " + format_number(tol->relative) + ", absolute " +
                  format_number(tol->absolute) + ", steps from tau up to " +
                  format_number(tol->max_step));
  }
  out.push_back("output: " + std::to_string(s.output.times.size()) + " frame(s)");
  return out;
}

}  // namespace sadr::orchestrator
