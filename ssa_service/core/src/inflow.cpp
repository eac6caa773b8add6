// SPDX-License-Identifier: MIT
#include "sadr/ssa/inflow.hpp"

#include <cmath>
#include <cstdint>

#include "sadr/ssa/nsm_solver.hpp"

namespace sadr::ssa {

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
