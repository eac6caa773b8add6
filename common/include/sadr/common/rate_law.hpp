// SPDX-License-Identifier: MIT
/// \file rate_law.hpp
/// THE rate law of a reaction, shared by both numerical cores (docs/method.md
/// section 4b): the SSA's propensities (ssa_service ReactionTable) and the
/// deterministic reaction rates (fluid_service SpeciesTransport).
///
/// A law gives the rate density v(C, t) [molecules/(L^d T)] of a reaction
/// from the local concentrations C; the stoichiometry comes from the reaction.
///
/// | type              | v                                   | reads           |
/// |-------------------|-------------------------------------|-----------------|
/// | mass action       | k prod_s C_s^nu_s / nu_s!           | the reactants   |
/// | Michaelis-Menten  | kcat C_E C_S / (Km + C_S)           | S and E         |
/// | Hill              | Vmax C_A^n / (K^n + C_A^n)          | A               |
/// | expression        | any muparser expression             | the species used|
///
/// Mass action keeps its own exact stochastic form (combinations, see
/// mass_action.hpp); for the other laws the SSA uses the standard
/// approximation a_i = V_i v(X_i / V_i), exact only for linear laws.
///
/// Expressions are parsed once (muparser, libmuparser-dev) with the parameters
/// folded in as constants; an evaluation copies the few concentrations into
/// the parser's bound variables and runs its bytecode: no allocation, no
/// string work. A RateLaw is NOT safe for concurrent evaluation (the bound
/// variables are its state): give each thread its own copy.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace sadr::rate_law {

enum class Type { kMassAction, kMichaelisMenten, kHill, kExpression };
std::string_view to_string(Type type);

/// A law as written (what the scene gives and the wire carries): species by
/// name, numbers already resolved. `origin` ("scene.yaml:12") prefixes errors.
struct Definition {
  Type type = Type::kMassAction;
  double k = 0;                                        ///< mass action: rate constant
  std::vector<std::pair<std::string, int>> reactants;  ///< mass action: (species, nu)
  double kcat = 0, km = 0;                             ///< Michaelis-Menten
  std::string substrate, catalyst;                     ///< Michaelis-Menten
  double vmax = 0, half = 0, n = 1;                    ///< Hill: Vmax, K, n
  std::string of;                                      ///< Hill: the species A
  std::string expression;                              ///< expression text
  std::map<std::string, double> parameters;            ///< named constants of the expression
  std::string origin;                                  ///< where it was written, for messages
  /// The law as a user would write it (for messages).
  [[nodiscard]] std::string text() const;
  bool operator==(const Definition&) const = default;
};

/// Admissible states sampled at load to refuse a negative or non-finite law.
struct SampleRange {
  double max_concentration = 1e3;  ///< grid points up to this concentration
  double end_time = 0;             ///< t in {0, end/2, end}
};

class RateLaw {
 public:
  /// Compiles `def` against the species names (index = position). Throws
  /// InvalidArgument naming origin, law and problem: unknown species or
  /// symbol, parse error, bad number (Km <= 0, K <= 0, n <= 0, negative
  /// constants), `t` where allow_time is false.
  RateLaw(const Definition& def, const std::vector<std::string>& species_names,
          bool allow_time = true);
  RateLaw(const RateLaw& other);
  RateLaw& operator=(const RateLaw& other);
  RateLaw(RateLaw&&) noexcept;
  RateLaw& operator=(RateLaw&&) noexcept;
  ~RateLaw();

  [[nodiscard]] Type type() const { return def_.type; }
  [[nodiscard]] const Definition& definition() const { return def_; }
  /// The species the law reads (distinct, ascending): the dependency of its
  /// propensity. density() takes their concentrations in this order.
  [[nodiscard]] const std::vector<int>& species() const { return species_; }
  /// Whether the law reads the time t.
  [[nodiscard]] bool uses_time() const { return uses_time_; }

  /// v(C, t) [molecules/(L^d T)]; c[k] = concentration of species()[k].
  [[nodiscard]] double density(const double* c, double t) const {
    switch (def_.type) {
      case Type::kMichaelisMenten:
        return def_.kcat * c[cat_] * c[sub_] / (def_.km + c[sub_]);
      case Type::kHill:
        return hill(c[0]);
      case Type::kExpression:
        return evaluate(c, t);
      case Type::kMassAction:
        break;
    }
    return mass_action(c);
  }

  /// d v / d C_k (k indexes species()) by a one-sided difference (for the
  /// deterministic time-step limit; not on the hot path).
  [[nodiscard]] double derivative(const double* c, double t, std::size_t k) const;

  /// Evaluates on a grid of admissible states (every species read in {0,
  /// 1e-3, 0.1, 1, 10, max}... within `range`, t in {0, end/2, end}); throws
  /// InvalidArgument with origin, law and the state if v < 0 or non-finite.
  void check_admissible(const SampleRange& range) const;

 private:
  [[nodiscard]] double hill(double a) const;
  [[nodiscard]] double mass_action(const double* c) const;
  [[nodiscard]] double evaluate(const double* c, double t) const;
  void compile_expression(const std::vector<std::string>& species_names, bool allow_time);
  [[nodiscard]] std::string where() const;

  Definition def_;
  std::vector<int> species_;
  std::vector<int> nu_;  ///< mass action: stoichiometry per species_
  int sub_ = 0, cat_ = 0;
  bool uses_time_ = false;
  struct Expression;
  std::unique_ptr<Expression> expr_;
  std::vector<std::string> names_;  ///< species names (copies rebuild the parser)
  bool allow_time_ = true;
};

}  // namespace sadr::rate_law
