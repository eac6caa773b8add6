// SPDX-License-Identifier: MIT
/// \file reaction_table.hpp
/// Reactions compiled for the event loop: per-voxel stochastic rate constants
/// (from mass_action::voxel_constant(), common/mass_action.hpp), kind/region
/// restrictions folded in, and Neumann sources appended as zeroth-order
/// reactions in the first fluid layer next to the walls.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "sadr/common/mass_action.hpp"
#include "sadr/common/rate_law.hpp"
#include "sadr/ssa/diffusion_graph.hpp"
#include "sadr/ssa/model.hpp"
#include "sadr/ssa/prefetch.hpp"

namespace sadr::ssa {

/// One reaction in event-loop form.
struct CompiledReaction {
  int law = -1;  ///< index into ReactionTable's laws, -1 = mass action
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
  /// Stochastic rate constant c of reaction r in voxel i [1/T]; for a rate
  /// law, V_i where it fires (else 0); for a boundary flux, A_i.
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
    if (rx.law >= 0) return a == 0 ? 0.0 : law_propensity(r, i, a, counts, n_voxels);
    for (int k = 0; k < rx.n_reactants; ++k) {
      a *= mass_action::combinations(counts[rx.species[k] * n_voxels + i], rx.nu[k]);
    }
    return a;
  }
  /// Number of rate-law reactions; law k belongs to reaction law_reaction(k).
  [[nodiscard]] std::size_t law_count() const { return laws_.size(); }
  [[nodiscard]] std::size_t law_reaction(int k) const { return laws_[k].reaction; }
  /// The rate law of reaction r (requires reaction(r).law >= 0).
  [[nodiscard]] const rate_law::RateLaw& law(std::size_t r) const {
    return laws_[reactions_[r].law].law;
  }
  /// Whether some law reads the time t or a frozen (deterministic) species.
  [[nodiscard]] bool has_external_laws() const { return has_external_; }
  /// Whether law k (of law_reaction(k)) reads t or a frozen species.
  [[nodiscard]] bool external(int k) const { return laws_[k].external; }
  /// Sets the inputs the external laws read: the time t and the frozen
  /// concentrations [(law species index - species count) * n_voxels + voxel].
  void set_inputs(double t, std::vector<double> frozen) {
    input_time_ = t;
    frozen_ = std::move(frozen);
  }
  [[nodiscard]] double input_time() const { return input_time_; }
  [[nodiscard]] const std::vector<double>& frozen() const { return frozen_; }

 private:
  /// a = c v(X / V_i) for rate-law reaction r in voxel i, c = constant(i, r): V_i for a volume
  /// law, A_i for a boundary flux (0 if a reactant has fewer molecules than its stoichiometry);
  /// throws NumericalFailure (reaction, voxel, counts) if a is negative or non-finite.
  [[nodiscard]] double law_propensity(std::size_t r, std::uint32_t i, double constant,
                                      const std::int64_t* counts, std::size_t n_voxels) const;

  struct LawEntry {
    rate_law::RateLaw law;
    std::vector<std::pair<int, int>> needs;  ///< reactants (species, nu): a = 0 if X < nu
    std::size_t reaction = 0;                ///< its reaction index
    bool external = false;                   ///< reads t or a frozen species
    bool areal = false;                      ///< a boundary flux: constant = A_i, not V_i
  };
  std::vector<LawEntry> laws_;
  int ns_ = 0;  ///< simulated species; law species >= ns_ are frozen
  bool has_external_ = false;
  double input_time_ = 0;                ///< t seen by the laws (set_inputs)
  std::vector<double> frozen_;           ///< frozen concentrations (set_inputs)
  std::vector<std::string> names_;       ///< reaction names (messages)
  std::vector<std::string> species_;     ///< species names (messages)
  mutable std::vector<double> scratch_;  ///< concentrations of one law evaluation
  std::vector<CompiledReaction> reactions_;
  std::vector<double> c_;             ///< [voxel * R + r]
  std::vector<std::uint8_t> active_;  ///< per voxel
  std::vector<double> volume_;        ///< V_i, kept only when a boundary flux needs it
};

}  // namespace sadr::ssa
