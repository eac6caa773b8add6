// SPDX-License-Identifier: MIT
// Scene section "parameters" and the "law" of a reaction (docs/scene-format.md).
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>

#include "sadr/common/status.hpp"
#include "scene_parts.hpp"

namespace sadr::orchestrator::detail {

namespace {

constexpr std::array<std::string_view, 3> kLawTypes{"michaelis_menten", "hill", "expression"};
constexpr std::array<std::string_view, 5> kMichaelisKeys{"type", "kcat", "Km", "catalyst",
                                                         "substrate"};
constexpr std::array<std::string_view, 5> kHillKeys{"type", "Vmax", "K", "n", "of"};
constexpr std::array<std::string_view, 2> kExpressionKeys{"type", "expression"};

/// A law number: a literal or the name of a top-level parameter.
std::optional<double> law_number(SceneContext& ctx, const Field& law, std::string_view key) {
  YamlReader& r = ctx.reader;
  const Field f = YamlReader::child(law, key);
  if (!YamlReader::present(f)) {
    r.error(f, "missing; required: a number or the name of a parameter");
    return std::nullopt;
  }
  if (f.node.IsScalar()) {
    const std::string& text = f.node.Scalar();
    if (!text.empty() && (std::isalpha(static_cast<unsigned char>(text[0])) || text[0] == '_')) {
      const auto it = ctx.scene.parameters.find(text);
      if (it != ctx.scene.parameters.end()) return it->second;
      std::vector<std::string_view> known;
      for (const auto& [name, value] : ctx.scene.parameters) known.push_back(name);
      std::string msg = "unknown parameter '" + text + "'";
      if (auto near = nearest_name(text, known)) msg += "; did you mean '" + *near + "'?";
      msg += " (parameters: " + (known.empty() ? std::string("none") : join_names(known)) + ")";
      r.error(f, msg);
      return std::nullopt;
    }
  }
  return r.number_at(f, Bound::kAny, "");
}

/// The one reactant of order 1 (Michaelis-Menten's substrate, Hill's default
/// `of`); reports and returns "" otherwise.
std::string single_reactant(SceneContext& ctx, const Field& where, const Reaction& rx,
                            std::string_view law) {
  if (rx.reactants.size() == 1 && rx.reactants[0].count == 1) return rx.reactants[0].species;
  ctx.reader.error(where, std::string(law) +
                              " needs exactly one reactant of stoichiometry 1 in the equation "
                              "(the substrate, e.g. \"S -> P\")");
  return "";
}

/// Replaces every whole-word occurrence of an assigned species by its
/// parenthesised expression (recursively; a cycle is reported).
std::string expand_assigned(SceneContext& ctx, const Field& where, const std::string& text,
                            int depth = 0) {
  if (depth > 16) {
    ctx.reader.error(where, "assigned species refer to each other in a cycle");
    return text;
  }
  std::string out;
  bool changed = false;
  for (std::size_t k = 0; k < text.size();) {
    const auto c = static_cast<unsigned char>(text[k]);
    if (std::isalpha(c) || c == '_') {
      std::size_t e = k;
      while (e < text.size() &&
             (std::isalnum(static_cast<unsigned char>(text[e])) || text[e] == '_'))
        ++e;
      const std::string word = text.substr(k, e - k);
      const AssignedSpecies* as = ctx.scene.find_assigned(word);
      if (as) {
        out += "(" + as->expression + ")";
        changed = true;
      } else {
        out += word;
      }
      k = e;
    } else if (std::isdigit(c) || c == '.') {  // a number, with its exponent (1e-3)
      std::size_t e = k;
      while (e < text.size() &&
             (std::isalnum(static_cast<unsigned char>(text[e])) || text[e] == '.' ||
              ((text[e] == '-' || text[e] == '+') && (text[e - 1] == 'e' || text[e - 1] == 'E')))) {
        ++e;
      }
      out += text.substr(k, e - k);
      k = e;
    } else {
      out += text[k++];
    }
  }
  return changed ? expand_assigned(ctx, where, out, depth + 1) : out;
}

}  // namespace

void read_parameters(SceneContext& ctx, const Field& root) {
  YamlReader& r = ctx.reader;
  const Field f = YamlReader::child(root, "parameters");
  if (!YamlReader::present(f)) return;
  if (!f.node.IsMap()) {
    r.error(f, "expected a map name: number (e.g. {kcat: 2.5, Km: 0.1})");
    return;
  }
  for (const auto& kv : f.node) {
    const std::string name = kv.first.Scalar();
    if (!valid_identifier(name) || name == "t") {
      r.error(YamlReader::child(f, name), "'" + name +
                                              "' is not a valid parameter name; allowed: "
                                              "[A-Za-z_][A-Za-z0-9_]* other than t (the time)");
      continue;
    }
    if (auto v = r.number(f, name, Bound::kAny, "", true)) ctx.scene.parameters[name] = *v;
  }
}

void check_parameter_names(SceneContext& ctx, const Field& root) {
  std::vector<std::string> names;
  for (const auto& sp : ctx.scene.species) names.push_back(sp.name);
  for (const auto& a : ctx.scene.assigned) names.push_back(a.name);
  for (const auto& name : names) {
    if (ctx.scene.parameters.count(name)) {
      ctx.reader.error(YamlReader::child(YamlReader::child(root, "parameters"), name),
                       "parameter '" + name +
                           "' has the name of a species; names in expressions must be unique");
    }
  }
}

void read_assigned(SceneContext& ctx, const Field& entry) {
  YamlReader& r = ctx.reader;
  constexpr std::array<std::string_view, 2> kKeys{"name", "assigned"};
  if (!r.expect_map(entry, kKeys)) return;
  AssignedSpecies a;
  a.name = r.string(entry, "name", true).value_or("");
  a.expression = r.string(entry, "assigned", true).value_or("");
  a.origin = ctx.scene.source_path.filename().string() + ":" +
             std::to_string(YamlReader::child(entry, "assigned").where.line);
  ctx.scene.assigned.push_back(std::move(a));
}

void check_assigned(SceneContext& ctx, const Field& root) {
  const Field list = YamlReader::child(root, "species");
  std::vector<std::string> names;
  for (const auto& sp : ctx.scene.species) names.push_back(sp.name);
  for (auto& a : ctx.scene.assigned) {
    Field where = list;
    for (std::size_t k = 0; k < list.node.size(); ++k) {
      const Field f = YamlReader::element(list, k);
      if (f.node.IsMap() && f.node["name"] && f.node["name"].Scalar() == a.name) {
        where = YamlReader::child(f, "assigned");
      }
    }
    if (a.expression.empty()) continue;
    a.expanded = expand_assigned(ctx, where, a.expression);
    rate_law::Definition d;
    d.type = rate_law::Type::kExpression;
    d.expression = a.expanded;
    d.parameters = ctx.scene.parameters;
    d.origin = a.origin;
    try {
      const rate_law::RateLaw law(d, names, false);
      law.check_admissible({});
    } catch (const InvalidArgument& e) {
      ctx.reader.error(where, std::string("assigned species '") + a.name + "': " + e.what());
    }
  }
}

bool read_law(SceneContext& ctx, const Field& reaction, Reaction& rx) {
  YamlReader& r = ctx.reader;
  const Field f = YamlReader::child(reaction, "law");
  if (!YamlReader::present(f)) return false;
  rate_law::Definition d;
  d.origin = ctx.scene.source_path.filename().string() + ":" + std::to_string(f.where.line);
  if (!f.node.IsMap()) {
    r.error(f, "expected a map {type: michaelis_menten | hill | expression, ...}");
    return true;
  }
  const auto type = r.choice(f, "type", kLawTypes, true, "law type");
  if (!type) return true;
  bool ok = true;
  auto number = [&](std::string_view key, double& out) {
    if (auto v = law_number(ctx, f, key)) {
      out = *v;
    } else {
      ok = false;
    }
  };
  auto species = [&](std::string_view key, bool required) -> std::string {
    auto name = r.string(f, key, required);
    if (!name) return "";
    if (!ctx.scene.find_species(*name)) {
      std::vector<std::string_view> known;
      for (const auto& sp : ctx.scene.species) known.push_back(sp.name);
      std::string msg = "unknown species '" + *name + "'";
      if (auto near = nearest_name(*name, known)) msg += "; did you mean '" + *near + "'?";
      r.error(YamlReader::child(f, key), msg);
      ok = false;
    }
    return *name;
  };
  if (*type == "michaelis_menten") {
    if (!r.expect_map(f, kMichaelisKeys)) return true;
    d.type = rate_law::Type::kMichaelisMenten;
    number("kcat", d.kcat);
    number("Km", d.km);
    d.catalyst = species("catalyst", true);
    if (YamlReader::present(YamlReader::child(f, "substrate"))) {
      d.substrate = species("substrate", true);
    } else {
      d.substrate = single_reactant(ctx, f, rx, "michaelis_menten");
    }
    for (const auto* side : {&rx.reactants, &rx.products}) {
      for (const auto& e : *side) {
        if (e.species == d.catalyst) {
          r.error(YamlReader::child(f, "catalyst"),
                  "the catalyst '" + d.catalyst +
                      "' appears in the equation; a catalyst is not consumed (leave it out)");
          ok = false;
        }
      }
    }
  } else if (*type == "hill") {
    if (!r.expect_map(f, kHillKeys)) return true;
    d.type = rate_law::Type::kHill;
    number("Vmax", d.vmax);
    number("K", d.half);
    number("n", d.n);
    d.of = YamlReader::present(YamlReader::child(f, "of")) ? species("of", true)
                                                           : single_reactant(ctx, f, rx, "hill");
  } else {
    if (!r.expect_map(f, kExpressionKeys)) return true;
    d.type = rate_law::Type::kExpression;
    const auto text = r.string(f, "expression", true);
    if (!text) return true;
    d.expression = expand_assigned(ctx, YamlReader::child(f, "expression"), *text);
    d.parameters = ctx.scene.parameters;
  }
  if (!ok || (d.substrate.empty() && d.type == rate_law::Type::kMichaelisMenten) ||
      (d.of.empty() && d.type == rate_law::Type::kHill)) {
    return true;
  }
  // Compile against every non-assigned species (the services compile against
  // theirs), then sample admissible states: wrong laws stop here, with file:line.
  std::vector<std::string> names;
  for (const auto& sp : ctx.scene.species) names.push_back(sp.name);
  try {
    const rate_law::RateLaw law(d, names);
    law.check_admissible({});
    rx.uses_time = law.uses_time();
    for (const int s : law.species()) {  // hybrid: species of the other path are read only
      const Species* sp = ctx.scene.find_species(names[s]);
      if (sp->stochastic != rx.stochastic) rx.reads_other.push_back(sp->name);
    }
  } catch (const InvalidArgument& e) {
    r.error(f, e.what());
    return true;
  }
  rx.law = std::move(d);
  return true;
}

}  // namespace sadr::orchestrator::detail
