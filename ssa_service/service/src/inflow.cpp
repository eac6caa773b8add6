// SPDX-License-Identifier: MIT
#include "sadr/ssa/inflow.hpp"

#include <cmath>
#include <cstdint>

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
    b.box = wire::from_proto(in, dimension, where);
    out.push_back(b);
  }
  return out;
}

bool apply_inflows(NsmSolver& solver, std::span<const InflowBuffer> inflows) {
  if (inflows.empty()) return false;
  const ParticleState& p = solver.state().graph_inputs();
  bool changed = false;
  for (const InflowBuffer& b : inflows) {
    const auto current = solver.counts(b.species);
    std::vector<std::int64_t> next(current.begin(), current.end());
    bool any = false;
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (!b.box.contains(&p.positions[3 * i])) continue;
      const auto target =
          static_cast<std::int64_t>(std::llround(b.box.concentration * p.volume(i)));
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
