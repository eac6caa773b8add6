// SPDX-License-Identifier: MIT
/// \file reaction_table.hpp
/// Reactions compiled for the event loop: per-voxel stochastic rate constants
/// (from mass_action::voxel_constant(), common/mass_action.hpp), kind/region
/// restrictions folded in, and Neumann sources appended as zeroth-order
/// reactions in the first fluid layer next to the walls.
#pragma once

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "sadr/common/mass_action.hpp"
#include "sadr/ssa/diffusion_graph.hpp"
#include "sadr/ssa/model.hpp"
#include "sadr/ssa/prefetch.hpp"

namespace sadr::ssa {

/// One reaction in event-loop form.
struct CompiledReaction {
  int order = 0;
  int n_reactants = 0;                      ///< 0, 1 or 2 distinct reactant species
  std::array<int, 2> species{0, 0};         ///< reactant species
  std::array<int, 2> nu{0, 0};              ///< their stoichiometries
  std::vector<std::pair<int, int>> change;  ///< net (species, delta != 0)
};

class ReactionTable {
 public:
  /// Compiles the model's reactions and Neumann sources on `graph`.
  static ReactionTable build(const Model& model, const DiffusionGraph& graph);

  [[nodiscard]] std::size_t reaction_count() const { return reactions_.size(); }
  [[nodiscard]] const CompiledReaction& reaction(std::size_t r) const { return reactions_[r]; }
  /// true if some reaction has a non-zero constant in voxel i.
  [[nodiscard]] bool active(std::uint32_t i) const { return active_[i] != 0; }
  /// Stochastic rate constant c of reaction r in voxel i [1/T].
  [[nodiscard]] double constant(std::uint32_t i, std::size_t r) const {
    return c_[i * reactions_.size() + r];
  }
  /// Hints that voxel i's constants are read soon (the event loop).
  void prefetch(std::uint32_t i) const {
    if (!reactions_.empty()) detail::prefetch_line(c_.data() + i * reactions_.size());
  }
  /// Propensity [1/T] of reaction r in voxel i; counts are species-major
  /// (X_si at counts[s * n_voxels + i]).
  [[nodiscard]] double propensity(std::size_t r, std::uint32_t i, const std::int64_t* counts,
                                  std::size_t n_voxels) const {
    const CompiledReaction& rx = reactions_[r];
    double a = constant(i, r);
    for (int k = 0; k < rx.n_reactants; ++k) {
      a *= mass_action::combinations(counts[rx.species[k] * n_voxels + i], rx.nu[k]);
    }
    return a;
  }

 private:
  std::vector<CompiledReaction> reactions_;
  std::vector<double> c_;             ///< [voxel * R + r]
  std::vector<std::uint8_t> active_;  ///< per voxel
};

}  // namespace sadr::ssa
