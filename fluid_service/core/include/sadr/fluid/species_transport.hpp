// SPDX-License-Identifier: MIT
/// \file species_transport.hpp
/// Deterministic species bookkeeping shared by every backend that transports species:
/// wall roles (Dirichlet / no-flux / Neumann) per particle and species, the pair
/// diffusion update of docs/method.md section 2, eq (17), and the reactions (common/rate_law.hpp).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "sadr/common/particle_state.hpp"
#include "sadr/fluid/fluid_model.hpp"

namespace sadr::fluid {

class SpeciesTransport {
 public:
  /// Role of a particle for one species.
  enum class Role : std::uint8_t { kFree, kNoFlux, kDirichlet, kNeumann };

  /// Resolves wall roles from the model's wall regions and compiles the reactions.
  void setup(const FluidModel& model, const ParticleState& state);

  /// Number of species integrated by the fluid (deterministic ones).
  [[nodiscard]] const std::vector<int>& transported() const { return transported_; }
  [[nodiscard]] Role role(int species, std::size_t i) const { return roles_[species][i]; }
  /// Sets every Dirichlet wall particle to its prescribed value.
  void apply_dirichlet(std::vector<std::vector<double>>& c) const;

  /// Adds the pair term of eq (17), docs/method.md, for every transported species to dc[s][i]:
  /// dc_i += k_ij (kappa_i + kappa_j)(C_j - C_i) with C_j replaced by the Neumann ghost value
  /// C_i + (q/kappa) x_ij . n_in for a Neumann wall j, skipped for a no-flux wall j.
  /// @param i a non-wall particle; @param k_ij DiffusionTerm coefficient [1/length^2];
  /// @param x_ij x_i - x_j (minimum image), 3 doubles.
  /// @param dirichlet_beta for a Dirichlet wall j, C_j is replaced by the extrapolated ghost
  /// value C_j + (beta - 1)(C_j - C_i), i.e. the pair term is multiplied by beta (Morris walls:
  /// the held value then sits on the wall surface; 1 = the held value at the particle).
  void add_pair(std::size_t i, std::size_t j, double k_ij, const double* x_ij,
                const std::vector<std::vector<double>>& c, std::vector<std::vector<double>>& dc,
                double dirichlet_beta = 1.0) const {
    for (const int s : transported_) {
      const Role rj = roles_[s][j];
      if (rj == Role::kFree) {
        dc[s][i] += k_ij * two_kappa_[s] * (c[s][j] - c[s][i]);
      } else if (rj == Role::kDirichlet) {
        dc[s][i] += dirichlet_beta * k_ij * two_kappa_[s] * (c[s][j] - c[s][i]);
      } else if (rj == Role::kNeumann) {
        const auto& n = normal_[region_[j]];
        const double xn = x_ij[0] * n[0] + x_ij[1] * n[1] + x_ij[2] * n[2];
        dc[s][i] += k_ij * two_kappa_[s] * neumann_grad_[s][region_[j] + 1] * xn;
      }
    }
  }
  /// add_pair for a wall particle i that is kFree for some species (WallCondition::kFree):
  /// only the species for which i itself is kFree are updated.
  void add_pair_wall(std::size_t i, std::size_t j, double k_ij, const double* x_ij,
                     const std::vector<std::vector<double>>& c,
                     std::vector<std::vector<double>>& dc) const {
    for (const int s : transported_) {
      if (roles_[s][i] != Role::kFree) continue;
      const Role rj = roles_[s][j];
      if (rj == Role::kFree || rj == Role::kDirichlet) {
        dc[s][i] += k_ij * two_kappa_[s] * (c[s][j] - c[s][i]);
      } else if (rj == Role::kNeumann) {
        const auto& n = normal_[region_[j]];
        const double xn = x_ij[0] * n[0] + x_ij[1] * n[1] + x_ij[2] * n[2];
        dc[s][i] += k_ij * two_kappa_[s] * neumann_grad_[s][region_[j] + 1] * xn;
      }
    }
  }
  /// True for a wall particle that takes part in species transport: kFree for some transported
  /// species or a site of some reaction (ReactionSpec::def.kinds contains kWall). Backends gather
  /// species terms for such walls with add_pair_wall() and call add_reactions() for them.
  [[nodiscard]] bool active_wall(std::size_t i) const { return active_wall_[i] != 0; }
  /// Adds the reaction rates (mass action or rate law) at particle i to dc (only reactions that
  /// fire at i: ReactionSpec::def.kinds and ::particles; held Dirichlet values are never changed).
  void add_reactions(std::size_t i, const std::vector<std::vector<double>>& c,
                     std::vector<std::vector<double>>& dc) const;
  /// max_i sum_r sum_{s in reactants} nu_s |dv_r/dC_s| [1/time]: the largest reaction
  /// Jacobian scale (exact eigenvalue for A + B -> 0), for the time-step limit.
  [[nodiscard]] double reaction_rate_scale(const std::vector<std::vector<double>>& c,
                                           const ParticleState& state) const;
  [[nodiscard]] double max_diffusivity() const { return max_kappa_; }
  [[nodiscard]] bool has_reactions() const { return !reactions_.empty(); }
  /// Re-derives the reaction sites from the particles' current kinds (ReactionSpec::def.kinds,
  /// still intersected with ReactionSpec::particles): for backends whose particles change
  /// kind (fluid <-> inlet <-> outlet at an open boundary). Wall particles never change kind,
  /// so wall roles and active_wall() stay as set up.
  void update_sites(std::span<const ParticleKind> kinds);
  [[nodiscard]] double two_kappa(int s) const { return two_kappa_[s]; }
  /// The time t the rate laws see in the next add_reactions / reaction_rate_scale calls
  /// (the integrator sets it per stage: docs/method.md section 4c).
  void set_time(double t) { time_ = t; }
  [[nodiscard]] double time() const { return time_; }

 private:
  struct Term {
    int species;
    int nu;
    double inv_factorial;
  };
  struct CompiledReaction {
    double rate;
    int law = -1;  // index into laws_[thread], -1 = mass action
    std::vector<Term> reactants;
    std::vector<std::pair<int, int>> delta;  // (species, net stoichiometry change)
    std::vector<std::uint8_t> fires;         // [particle] 1 where the reaction fires
    std::array<std::uint8_t, 4> kind_ok{};   // [kind] 1 if the reaction fires on that kind
    std::vector<std::uint8_t> listed;        // [particle] in ReactionSpec::particles (empty: all)
    std::vector<double> scale;  // [particle] boundary flux: A_i / V_i (empty: a volume rate, 1)
  };
  [[nodiscard]] double velocity(const CompiledReaction& r, std::size_t i,
                                const std::vector<std::vector<double>>& c) const;
  [[nodiscard]] double law_rate_scale(const CompiledReaction& r, std::size_t i,
                                      const std::vector<std::vector<double>>& c) const;

  std::vector<int> transported_;
  std::vector<double> two_kappa_;
  double max_kappa_ = 0;
  std::vector<std::vector<Role>> roles_;           // [species][particle]
  std::vector<std::int32_t> region_;               // particle -> wall region index (-1 none)
  std::vector<std::array<double, 3>> normal_;      // per region
  std::vector<std::vector<double>> neumann_grad_;  // [species][region + 1] = q / kappa
  std::vector<std::vector<double>> dirichlet_;     // [species][region + 1] = value
  std::vector<CompiledReaction> reactions_;
  /// Rate laws, one copy per thread (a RateLaw's evaluation is not reentrant):
  /// laws_[thread][law]; scratch_[thread] holds one law's concentrations.
  mutable std::vector<std::vector<rate_law::RateLaw>> laws_;
  mutable std::vector<std::vector<double>> scratch_;
  std::vector<std::uint8_t> reacts_;       // some reaction fires at the particle
  std::vector<std::uint8_t> active_wall_;  // wall particle with species transport (see above)
  double time_ = 0;                        // t of the rate laws (set_time)
};

}  // namespace sadr::fluid
