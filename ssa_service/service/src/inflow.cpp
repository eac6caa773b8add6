// SPDX-License-Identifier: MIT
#include "sadr/ssa/inflow.hpp"

#include <cmath>
#include <cstdint>
#include <limits>

#include "sadr/common/status.hpp"
#include "sadr/ssa/nsm_solver.hpp"

namespace sadr::ssa {

std::vector<InflowBuffer> inflows_from_proto(const v1::SsaModel& model, int dimension,
                                             const std::vector<std::string>& species_names) {
  std::vector<InflowBuffer> out;
  for (int k = 0; k < model.inflows_size(); ++k) {
    const auto& in = model.inflows(k);
    const std::string where = "init.model.inflows[" + std::to_string(k) + "]";
    InflowBuffer b;
    b.species = -1;
    for (std::size_t s = 0; s < species_names.size(); ++s) {
      if (species_names[s] == in.species()) b.species = static_cast<int>(s);
    }
    if (b.species < 0) {
      throw InvalidArgument(
          where + ".species = '" + in.species() + "' is not a stochastic species of the model",
          {{"field", where + ".species"}, {"value", in.species()}});
    }
    if (in.lower_size() != dimension || in.upper_size() != dimension) {
      throw InvalidArgument(where + ": lower/upper have " + std::to_string(in.lower_size()) + "/" +
                                std::to_string(in.upper_size()) + " entries (allowed: " +
                                std::to_string(dimension) + ", one per axis)",
                            {{"field", where + ".lower"}});
    }
    constexpr double kInf = std::numeric_limits<double>::infinity();
    b.lower = {-kInf, -kInf, -kInf};
    b.upper = {kInf, kInf, kInf};
    for (int a = 0; a < dimension; ++a) {
      b.lower[a] = in.lower(a);
      b.upper[a] = in.upper(a);
      if (std::isnan(b.lower[a]) || std::isnan(b.upper[a]) || !(b.lower[a] <= b.upper[a])) {
        throw InvalidArgument(
            where + ": axis " + std::to_string(a) + " has lower = " + format_value(b.lower[a]) +
                " > upper = " + format_value(b.upper[a]) + " (allowed: lower <= upper)",
            {{"field", where + ".lower"}});
      }
    }
    b.concentration = in.concentration();
    if (!std::isfinite(b.concentration) || b.concentration < 0) {
      throw InvalidArgument(
          where + ".concentration = " + format_value(b.concentration) +
              " (allowed: finite, >= 0 molecules/length^d)",
          {{"field", where + ".concentration"}, {"value", format_value(b.concentration)}});
    }
    out.push_back(b);
  }
  return out;
}

bool apply_inflows(NsmSolver& solver, std::span<const InflowBuffer> inflows) {
  if (inflows.empty()) return false;
  const ParticleState& p = solver.state().graph_inputs();
  const int dim = p.dimension;
  bool changed = false;
  for (const InflowBuffer& b : inflows) {
    const auto current = solver.counts(b.species);
    std::vector<std::int64_t> next(current.begin(), current.end());
    bool any = false;
    for (std::size_t i = 0; i < p.size(); ++i) {
      bool inside = true;
      for (int a = 0; a < dim && inside; ++a) {
        const double x = p.positions[3 * i + static_cast<std::size_t>(a)];
        inside = x >= b.lower[a] && x <= b.upper[a];
      }
      if (!inside) continue;
      const auto target = static_cast<std::int64_t>(std::llround(b.concentration * p.volume(i)));
      if (next[i] != target) next[i] = target, any = true;
    }
    if (any) {
      solver.set_counts(b.species, next);
      changed = true;
    }
  }
  return changed;
}

}  // namespace sadr::ssa
