// SPDX-License-Identifier: MIT
#include "sadr/fluid/fluid_model.hpp"

#include <cmath>
#include <string>
#include <utility>

#include "sadr/common/status.hpp"
#include "sadr/fluid/kernel.hpp"
#include "sadr/model/chemistry.hpp"

namespace sadr::fluid {

SpeciesSpec::SpeciesSpec(std::string name, double diffusivity, bool deterministic,
                         WallCondition default_wall, std::vector<WallCondition> wall_conditions)
    : default_wall(default_wall), wall_conditions(std::move(wall_conditions)) {
  def.name = std::move(name);
  def.stochastic = !deterministic;
  def.diffusivity = diffusivity;
}

ReactionSpec::ReactionSpec(std::string name, std::vector<std::pair<int, int>> reactants,
                           std::vector<std::pair<int, int>> products, double rate,
                           std::vector<ParticleKind> kinds, std::vector<std::uint32_t> particles)
    : reactants(std::move(reactants)),
      products(std::move(products)),
      particles(std::move(particles)) {
  def.name = std::move(name);
  def.rate = rate;
  def.kinds = std::move(kinds);
}

KernelType parse_kernel(std::string_view name) {
  if (name == "lucy") return KernelType::kLucy;
  if (name == "wendland_c2") return KernelType::kWendlandC2;
  throw InvalidArgument(
      "kernel = '" + std::string(name) + "' is unknown (known: lucy, wendland_c2)",
      {{"field", "kernel"}, {"value", std::string(name)}});
}

namespace {
using model::Problems;
}  // namespace

void FluidModel::validate() const {
  Problems p;
  try {
    box.validate();
  } catch (const Error& e) {
    p.add_text("box", e.what());
  }
  p.finite_positive("smoothing_length", smoothing_length);
  if (kernel != "lucy" && kernel != "wendland_c2") {
    p.add_text("kernel", "'" + kernel + "' is unknown (known: lucy, wendland_c2)");
  }
  p.finite_positive("reference_density", reference_density);
  // 0 = not given: only backends with an equation of state need c_0 (sdpd checks it).
  p.finite_nonneg("sound_speed", sound_speed);
  p.finite_nonneg("shear_viscosity", shear_viscosity);
  p.finite_nonneg("temperature", temperature);
  if (temperature > 0 && shear_viscosity <= 0) {
    p.add("temperature", temperature,
          "thermal noise needs shear_viscosity > 0 (fluctuation-dissipation)");
  }
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(gravity[a]))
      p.add("gravity[" + std::to_string(a) + "]", gravity[a], "finite");
  }
  p.finite_nonneg("density_diffusion", density_diffusion);
  p.finite_nonneg("diffusion_eps", diffusion_eps);
  p.finite_nonneg("max_time_step", max_time_step);  // 0 = automatic
  if (!(density_band > 0 && density_band < 1)) p.add("density_band", density_band, "in (0, 1)");
  if (!(neighbor_skin >= 0 && neighbor_skin <= 1))
    p.add("neighbor_skin", neighbor_skin, "in [0, 1]");
  const int ns = static_cast<int>(species.size());
  for (int s = 0; s < ns; ++s) {
    const auto& sp = species[s];
    const std::string f = "species[" + std::to_string(s) + "]";
    if (sp.def.name.empty()) p.add_text(f + ".name", "must not be empty");
    for (int t = 0; t < s; ++t) {
      if (species[t].def.name == sp.def.name && !sp.def.name.empty())
        p.add_text(f + ".name", "duplicate '" + sp.def.name + "'");
    }
    p.finite_nonneg(f + ".diffusivity", sp.def.diffusivity);
    if (!sp.wall_conditions.empty() && sp.wall_conditions.size() != wall_regions.size()) {
      p.add(f + ".wall_conditions size", static_cast<double>(sp.wall_conditions.size()),
            "0 or the number of wall_regions (" + std::to_string(wall_regions.size()) + ")");
    }
    auto check_wc = [&](const WallCondition& wc, const std::string& name) {
      if (!std::isfinite(wc.value)) p.add(name + ".value", wc.value, "finite");
      if (wc.type == WallCondition::Type::kNeumann && sp.def.diffusivity <= 0) {
        p.add(f + ".diffusivity", sp.def.diffusivity, "a Neumann wall needs diffusivity > 0");
      }
    };
    check_wc(sp.default_wall, f + ".default_wall");
    for (std::size_t w = 0; w < sp.wall_conditions.size(); ++w) {
      check_wc(sp.wall_conditions[w], f + ".wall_conditions[" + std::to_string(w) + "]");
    }
  }
  for (std::size_t r = 0; r < reactions.size(); ++r) {
    const auto& re = reactions[r];
    const std::string f = "reactions[" + std::to_string(r) + "]";
    model::ReactionNumbers numbers;
    numbers.rate = re.def.rate;
    numbers.has_law = re.def.law.has_value();
    numbers.areas = &re.def.boundary_areas;
    numbers.sites = re.particles.size();
    auto check_side = [&](const std::vector<std::pair<int, int>>& side, const std::string& nm,
                          std::vector<long>& counts) {
      for (const auto& [s, nu] : side) {
        if (s < 0 || s >= ns) {
          p.add(f + "." + nm + " species", s, "must index species [0, " + std::to_string(ns) + ")");
        } else if (!species[s].deterministic()) {
          p.add_text(f + "." + nm,
                     "species '" + species[s].def.name +
                         "' is stochastic; fluid reactions use deterministic species only");
        }
        counts.push_back(nu);
      }
    };
    check_side(re.reactants, "reactants", numbers.reactant_counts);
    check_side(re.products, "products", numbers.product_counts);
    model::Problems problems;
    problems.set_prefix(f);
    model::check(numbers, problems);
    for (const auto& q : problems.list()) p.add(q.field, q.value, q.allowed);
    if (re.def.law) {
      std::vector<std::string> names;
      for (const auto& sp : species) names.push_back(sp.def.name);
      try {
        // A law may read stochastic species (hybrid reactions: their concentrations
        // X / V come with each advance, the back-transfer) and the time t.
        (void)rate_law::RateLaw(*re.def.law, names);
      } catch (const InvalidArgument& e) {
        p.add_text(f + ".law", e.what());
      }
    }
  }
  if (boussinesq.species >= ns || boussinesq.species < -1) {
    p.add("boussinesq.species", boussinesq.species,
          "-1 (off) or a species index < " + std::to_string(ns));
  }
  if (!std::isfinite(boussinesq.coefficient) || !std::isfinite(boussinesq.reference)) {
    p.add("boussinesq.coefficient", boussinesq.coefficient,
          "coefficient and reference must be finite");
  }
  for (std::size_t w = 0; w < wall_regions.size(); ++w) {
    const auto& n = wall_regions[w].inward_normal;
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(std::fabs(len - 1.0) < 1e-6)) {
      p.add("wall_regions[" + std::to_string(w) + "].inward_normal |n|", len, "a unit vector");
    }
  }
  for (std::size_t b = 0; b < moving_bodies.size(); ++b) {
    const std::string f = "moving_bodies[" + std::to_string(b) + "].";
    const RigidMotion& m = moving_bodies[b].motion;
    for (int a = 0; a < 3; ++a) {
      if (!std::isfinite(m.velocity[a])) {
        p.add(f + "velocity[" + std::to_string(a) + "]", m.velocity[a], "finite");
      }
      if (!std::isfinite(m.center[a])) {
        p.add(f + "center[" + std::to_string(a) + "]", m.center[a], "finite");
      }
    }
    if (!std::isfinite(m.angular_velocity)) {
      p.add(f + "angular_velocity", m.angular_velocity, "finite");
    }
    const auto& n = m.axis;
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(std::fabs(len - 1.0) < 1e-6)) p.add(f + "axis |n|", len, "a unit vector");
    // Morris: each wall particle's own tangent plane, relative to it, moves with a translation;
    // the regions' surfaces (wall_regions) and a turning body's planes do not.
    if (wall_model == WallModel::kMorrisExtrapolated && wall_tangents.empty()) {
      p.add(f + "wall_model", 1.0,
            "stationary or adami, or morris with wall_tangents (the regions' wall surfaces do "
            "not move)");
    }
    if (wall_model == WallModel::kMorrisExtrapolated && m.angular_velocity != 0.0) {
      p.add(f + "angular_velocity", m.angular_velocity,
            "0 with wall_model morris (its tangent planes do not turn), or wall_model stationary "
            "or adami");
    }
  }
  if (open_boundary.enabled) {
    const auto& ob = open_boundary;
    const int d = box.dimension;
    const std::string f = "open_boundary";
    if (ob.axis < 0 || ob.axis >= d) {
      p.add(f + ".axis", ob.axis, "an active axis [0, " + std::to_string(d) + ")");
    } else {
      const int a = ob.axis;
      if (box.periodic[a]) p.add_text(f + ".axis", "the flow axis must be walled, not periodic");
      const double hs = smoothing_length;
      if (!(ob.inlet_lo >= box.lo[a] && ob.outlet_hi <= box.hi[a])) {
        p.add(f + ".inlet_lo", ob.inlet_lo,
              "inlet_lo and outlet_hi (" + format_value(ob.outlet_hi) +
                  ") must lie inside the box [" + format_value(box.lo[a]) + ", " +
                  format_value(box.hi[a]) + "] along the flow axis");
      }
      if (!(ob.fluid_lo - ob.inlet_lo >= hs)) {
        p.add(f + ".inlet length", ob.fluid_lo - ob.inlet_lo,
              "fluid_lo - inlet_lo must be >= the kernel support h = " + format_value(hs));
      }
      if (!(ob.outlet_hi - ob.fluid_hi >= hs)) {
        p.add(f + ".outlet length", ob.outlet_hi - ob.fluid_hi,
              "outlet_hi - fluid_hi must be >= the kernel support h = " + format_value(hs));
      }
      if (!(ob.fluid_hi > ob.fluid_lo)) {
        p.add(f + ".fluid_hi", ob.fluid_hi, "> fluid_lo = " + format_value(ob.fluid_lo));
      }
    }
    if (!(std::isfinite(ob.mean_velocity) && ob.mean_velocity > 0)) {
      p.add(f + ".mean_velocity", ob.mean_velocity, "finite and > 0 (flow along +axis)");
    }
    if (ob.profile == OpenBoundary::Profile::kParabolic) {
      if (ob.cross_axis < 0 || ob.cross_axis >= d || ob.cross_axis == ob.axis) {
        p.add(f + ".cross_axis", ob.cross_axis,
              "a parabolic profile needs an active axis other than the flow axis");
      }
      if (!(std::isfinite(ob.wall_lo) && std::isfinite(ob.wall_hi) && ob.wall_hi > ob.wall_lo)) {
        p.add(f + ".wall_hi", ob.wall_hi, "finite and > wall_lo = " + format_value(ob.wall_lo));
      }
    }
  }
  p.throw_if_any("invalid fluid model");
}

std::vector<std::int32_t> FluidModel::assign_wall_regions(const ParticleState& state) const {
  const std::size_t n = state.size();
  std::vector<std::int32_t> region(n, -1);
  for (std::size_t w = wall_regions.size();
       w-- > 0;) {  // reverse: earlier regions overwrite later ones
    const auto& reg = wall_regions[w];
    if (!reg.particles.empty()) {
      for (const auto k : reg.particles) {
        if (k >= n) {
          throw InvalidArgument("wall_regions[" + std::to_string(w) + "] ('" + reg.name +
                                "') lists particle " + std::to_string(k) + ", but there are " +
                                std::to_string(n));
        }
        if (state.kind(k) == ParticleKind::kWall) region[k] = static_cast<std::int32_t>(w);
      }
      continue;
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (state.kind(i) != ParticleKind::kWall) continue;
      bool in = true;
      for (int a = 0; a < box.dimension; ++a) {
        const double x = state.positions[3 * i + a];
        in = in && x >= reg.lo[a] && x <= reg.hi[a];
      }
      if (in) region[i] = static_cast<std::int32_t>(w);
    }
  }
  return region;
}

int FluidModel::species_index(const std::string& name) const {
  for (std::size_t s = 0; s < species.size(); ++s) {
    if (species[s].def.name == name) return static_cast<int>(s);
  }
  return -1;
}

}  // namespace sadr::fluid
