// SPDX-License-Identifier: MIT
#include "sadr/common/rate_law.hpp"

#include <muParser.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <sstream>

#include "sadr/common/mass_action.hpp"
#include "sadr/common/status.hpp"

namespace sadr::rate_law {

namespace {

std::string number(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out.empty() ? "none" : out;
}

}  // namespace

std::string_view to_string(Type type) {
  switch (type) {
    case Type::kMassAction:
      return "mass_action";
    case Type::kMichaelisMenten:
      return "michaelis_menten";
    case Type::kHill:
      return "hill";
    case Type::kExpression:
      return "expression";
  }
  return "?";
}

std::string Definition::text() const {
  switch (type) {
    case Type::kMassAction: {
      std::string r;
      for (const auto& [s, nu] : reactants) {
        r.append(" ").append(s);
        if (nu > 1) r.append("^").append(std::to_string(nu));
      }
      return "mass_action k = " + number(k) + (r.empty() ? "" : " of" + r);
    }
    case Type::kMichaelisMenten:
      return "michaelis_menten kcat = " + number(kcat) + ", Km = " + number(km) +
             ", catalyst = " + catalyst + ", substrate = " + substrate;
    case Type::kHill:
      return "hill Vmax = " + number(vmax) + ", K = " + number(half) + ", n = " + number(n) +
             ", of = " + of;
    case Type::kExpression:
      return "expression \"" + expression + "\"";
  }
  return "?";
}

/// The parsed expression: a muparser Parser whose variables are bound to
/// `vars` (the law's species in order, then t).
struct RateLaw::Expression {
  mu::Parser parser;
  std::vector<double> vars;
};

RateLaw::RateLaw(const Definition& def, const std::vector<std::string>& species_names,
                 bool allow_time)
    : def_(def), names_(species_names), allow_time_(allow_time) {
  auto index = [&](const std::string& name, const char* field) {
    auto it = std::find(species_names.begin(), species_names.end(), name);
    if (it == species_names.end()) {
      throw InvalidArgument(where() + field + " = '" + name +
                            "' is not a species of this model (species: " + join(species_names) +
                            ")");
    }
    return static_cast<int>(it - species_names.begin());
  };
  auto positive = [&](double v, const char* field) {
    if (!(v > 0) || !std::isfinite(v)) {
      throw InvalidArgument(where() + field + " = " + number(v) +
                            " is out of range; allowed: a finite number > 0");
    }
  };
  auto non_negative = [&](double v, const char* field) {
    if (!(v >= 0) || !std::isfinite(v)) {
      throw InvalidArgument(where() + field + " = " + number(v) +
                            " is out of range; allowed: a finite number >= 0");
    }
  };
  switch (def_.type) {
    case Type::kMassAction: {
      non_negative(def_.k, "k");
      std::map<int, int> nu;
      for (const auto& [s, n] : def_.reactants) nu[index(s, "reactant")] += n;
      for (const auto& [s, n] : nu) species_.push_back(s), nu_.push_back(n);
      break;
    }
    case Type::kMichaelisMenten: {
      non_negative(def_.kcat, "kcat");
      positive(def_.km, "Km");
      const int s = index(def_.substrate, "substrate");
      const int e = index(def_.catalyst, "catalyst");
      if (s == e)
        throw InvalidArgument(where() + "the catalyst is the substrate '" + def_.substrate + "'");
      species_ = {std::min(s, e), std::max(s, e)};
      sub_ = s < e ? 0 : 1;
      cat_ = 1 - sub_;
      break;
    }
    case Type::kHill:
      non_negative(def_.vmax, "Vmax");
      positive(def_.half, "K");
      positive(def_.n, "n");
      species_ = {index(def_.of, "of")};
      break;
    case Type::kExpression:
      compile_expression(species_names, allow_time);
      break;
  }
}

RateLaw::RateLaw(const RateLaw& other) : RateLaw(other.def_, other.names_, other.allow_time_) {}
RateLaw& RateLaw::operator=(const RateLaw& other) {
  if (this != &other) *this = RateLaw(other);
  return *this;
}
RateLaw::RateLaw(RateLaw&&) noexcept = default;
RateLaw& RateLaw::operator=(RateLaw&&) noexcept = default;
RateLaw::~RateLaw() = default;

std::string RateLaw::where() const {
  return (def_.origin.empty() ? std::string() : def_.origin + ": ") + "rate law " + def_.text() +
         ": ";
}

void RateLaw::compile_expression(const std::vector<std::string>& species_names, bool allow_time) {
  if (def_.expression.find_first_not_of(" \t") == std::string::npos) {
    throw InvalidArgument(where() + "the expression is empty");
  }
  for (const auto& [name, value] : def_.parameters) {
    if (std::find(species_names.begin(), species_names.end(), name) != species_names.end()) {
      throw InvalidArgument(where() + "parameter '" + name + "' has the name of a species");
    }
    if (name == "t") throw InvalidArgument(where() + "parameter 't' shadows the time t");
    if (!std::isfinite(value)) {
      throw InvalidArgument(where() + "parameter '" + name + "' = " + number(value) +
                            " is not finite");
    }
  }
  // First pass: every species, parameter and t bound, to learn which ones the
  // expression uses (muparser reports an unknown symbol as an unassignable token).
  std::vector<double> all(species_names.size() + 1, 1.0);
  std::set<std::string> used;
  auto refuse = [&](const mu::Parser::exception_type& e) {
    std::string msg = e.GetMsg();
    if (e.GetCode() == mu::ecUNASSIGNABLE_TOKEN || e.GetCode() == mu::ecUNEXPECTED_VAR) {
      std::vector<std::string> params;
      for (const auto& [name, value] : def_.parameters) params.push_back(name);
      msg = "unknown symbol '" + e.GetToken() + "' at position " + std::to_string(e.GetPos()) +
            " (known: species " + join(species_names) + "; parameters " + join(params) +
            "; the time t)";
    }
    throw InvalidArgument(where() + msg);
  };
  try {
    mu::Parser probe;
    for (std::size_t s = 0; s < species_names.size(); ++s)
      probe.DefineVar(species_names[s], &all[s]);
    for (const auto& [name, value] : def_.parameters) probe.DefineConst(name, value);
    probe.DefineVar("t", &all.back());
    probe.SetExpr(def_.expression);
    (void)probe.Eval();  // throws for unknown symbols and syntax errors
    for (const auto& [name, ptr] : probe.GetUsedVar()) used.insert(name);
  } catch (const mu::Parser::exception_type& e) {
    refuse(e);
  }
  uses_time_ = used.count("t") > 0;
  if (uses_time_ && !allow_time) {
    throw InvalidArgument(where() +
                          "reads the time t, which rate laws do not support yet (the SSA would "
                          "need propensities that change between events, the fluid the stage "
                          "time)");
  }
  for (std::size_t s = 0; s < species_names.size(); ++s) {
    if (used.count(species_names[s])) species_.push_back(static_cast<int>(s));
  }
  expr_ = std::make_unique<Expression>();
  expr_->vars.assign(species_.size() + 1, 0.0);
  for (std::size_t k = 0; k < species_.size(); ++k) {
    expr_->parser.DefineVar(species_names[species_[k]], &expr_->vars[k]);
  }
  expr_->parser.DefineVar("t", &expr_->vars.back());
  for (const auto& [name, value] : def_.parameters) expr_->parser.DefineConst(name, value);
  expr_->parser.SetExpr(def_.expression);
  try {
    (void)expr_->parser.Eval();  // compiles to bytecode now, not on the first hot call
  } catch (const mu::Parser::exception_type& e) {
    refuse(e);
  }
}

double RateLaw::hill(double a) const {
  const double an = std::pow(a, def_.n);
  return def_.vmax * an / (std::pow(def_.half, def_.n) + an);
}

double RateLaw::mass_action(const double* c) const {
  double v = def_.k;
  for (std::size_t k = 0; k < species_.size(); ++k) {
    v *= mass_action::concentration_term(c[k], nu_[k], mass_action::inverse_factorial(nu_[k]));
  }
  return v;
}

double RateLaw::evaluate(const double* c, double t) const {
  double* vars = expr_->vars.data();
  const std::size_t n = species_.size();
  for (std::size_t k = 0; k < n; ++k) vars[k] = c[k];
  vars[n] = t;
  return expr_->parser.Eval();
}

double RateLaw::derivative(const double* c, double t, std::size_t k) const {
  std::array<double, 64> local{};
  std::vector<double> heap;
  double* x = local.data();
  if (species_.size() > local.size()) {
    heap.assign(c, c + species_.size());
    x = heap.data();
  } else {
    std::copy(c, c + species_.size(), x);
  }
  const double h = std::max(1e-9, 1e-6 * std::fabs(c[k]));
  const double v0 = density(x, t);
  x[k] = c[k] + h;
  return (density(x, t) - v0) / h;
}

void RateLaw::check_admissible(const SampleRange& range) const {
  const double top = std::max(range.max_concentration, 1.0);
  const std::array<double, 7> levels{0.0, 1e-3 * top, 1e-3, 0.1, 1.0, 10.0, top};
  const std::array<double, 3> times{0.0, 0.5 * range.end_time, range.end_time};
  const std::size_t ns = species_.size();
  std::vector<double> c(ns, 0.0);
  // The full grid for up to 4 species (7^4 points), else every species alone
  // at each level with the others at each common level (7 * ns * 7 points).
  auto test = [&](double t) {
    const double v = density(c.data(), t);
    if (std::isfinite(v) && v >= 0) return;
    std::string state;
    for (std::size_t k = 0; k < ns; ++k) {
      state += (k ? ", " : "") + names_[species_[k]] + " = " + number(c[k]);
    }
    if (uses_time_) state += (ns ? ", " : "") + std::string("t = ") + number(t);
    throw InvalidArgument(where() + "v = " + number(v) + " at the admissible state {" + state +
                          "}; allowed: a finite rate >= 0 at every state with concentrations "
                          ">= 0");
  };
  for (const double t : times) {
    if (!uses_time_ && t != times[0]) break;
    if (ns <= 4) {
      std::size_t total = 1;
      for (std::size_t k = 0; k < ns; ++k) total *= levels.size();
      for (std::size_t p = 0; p < total; ++p) {
        std::size_t q = p;
        for (std::size_t k = 0; k < ns; ++k) c[k] = levels[q % levels.size()], q /= levels.size();
        test(t);
      }
    } else {
      for (const double base : levels) {
        for (std::size_t k = 0; k < ns; ++k) {
          for (const double lv : levels) {
            std::fill(c.begin(), c.end(), base);
            c[k] = lv;
            test(t);
          }
        }
      }
    }
  }
}

}  // namespace sadr::rate_law
