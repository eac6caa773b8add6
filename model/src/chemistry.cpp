// SPDX-License-Identifier: MIT
#include "sadr/model/chemistry.hpp"

#include <cmath>
#include <string>

namespace sadr::model {

std::string_view to_string(BoundaryCondition condition) {
  switch (condition) {
    case BoundaryCondition::kNone:
      return "none";
    case BoundaryCondition::kDirichlet:
      return "dirichlet";
    case BoundaryCondition::kNeumann:
      return "neumann";
    case BoundaryCondition::kFree:
      return "free";
    case BoundaryCondition::kInflow:
      return "inflow";
  }
  return "unknown";
}

std::string_view to_string(JumpConvention convention) {
  return convention == JumpConvention::kVolume ? "volume" : "symmetric";
}

unsigned Reaction::order() const {
  unsigned n = 0;
  for (const auto& e : reactants) n += e.count;
  return n;
}

void check(const Species& species, Problems& out) {
  out.finite_nonneg("diffusivity", species.diffusivity);
  for (std::size_t k = 0; k < species.boundaries.size(); ++k) {
    const SpeciesBoundary& b = species.boundaries[k];
    const std::string field = "boundaries[" + std::to_string(k) + "].value";
    switch (b.condition) {
      case BoundaryCondition::kDirichlet:
      case BoundaryCondition::kInflow:
        out.finite_nonneg(field, b.value);  // a concentration
        break;
      case BoundaryCondition::kNeumann:  // an inward flux density; negative is outward
        if (!std::isfinite(b.value)) out.add(field, b.value, "finite");
        break;
      case BoundaryCondition::kNone:
      case BoundaryCondition::kFree:
        break;
    }
  }
}

void check(const ReactionNumbers& rx, Problems& out) {
  out.finite_nonneg("rate", rx.rate);
  long order = 0;
  auto side = [&](const std::vector<long>& counts, const char* name) {
    for (std::size_t k = 0; k < counts.size(); ++k) {
      if (counts[k] < 1) {
        out.add(std::string(name) + "[" + std::to_string(k) + "].count", std::to_string(counts[k]),
                ">= 1");
      }
    }
  };
  side(rx.reactant_counts, "reactants");
  side(rx.product_counts, "products");
  for (long c : rx.reactant_counts) order += c;
  if (!rx.has_law && order > 2) {
    out.add_text("reactants", "order " + std::to_string(order) +
                                  " is not allowed; allowed: mass-action order 0, 1 or 2 "
                                  "(split higher-order reactions into elementary steps, or give "
                                  "a law)");
  }
  if (rx.areas == nullptr || rx.areas->empty()) return;
  if (!rx.has_law) out.add_text("boundary_areas", "a boundary flux needs a law");
  if (rx.areas->size() != rx.sites) {
    out.add("boundary_areas", std::to_string(rx.areas->size()) + " areas",
            "one per site: " + std::to_string(rx.sites));
  }
  for (std::size_t k = 0; k < rx.areas->size(); ++k) {
    out.finite_positive("boundary_areas[" + std::to_string(k) + "]", (*rx.areas)[k]);
  }
}

void check(const Reaction& reaction, Problems& out) {
  ReactionNumbers n;
  n.rate = reaction.rate;
  for (const auto& e : reaction.reactants) n.reactant_counts.push_back(e.count);
  for (const auto& e : reaction.products) n.product_counts.push_back(e.count);
  n.has_law = reaction.law.has_value();
  n.areas = &reaction.boundary_areas;
  n.sites = reaction.boundary_particles.size();
  check(n, out);
}

std::string_view to_string(SsaMethod method) {
  return method == SsaMethod::kAdaptive ? "adaptive" : "exact";
}

void check(const SsaSettings& ssa, Problems& out) {
  out.finite_nonneg("regularization", ssa.regularization);
  if (!(ssa.tolerance > 0 && ssa.tolerance < 1)) {
    out.add("tolerance", ssa.tolerance, "0 < tolerance < 1");
  }
}

}  // namespace sadr::model
