// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/reaction_equation.hpp"

#include <cctype>
#include <string>

#include "sadr/common/status.hpp"

namespace sadr::orchestrator {

namespace {

std::string trim(std::string_view s) {
  std::size_t b = 0;
  std::size_t e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return std::string(s.substr(b, e - b));
}

bool identifier(std::string_view s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  for (const char c : s) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  }
  return true;
}

std::vector<StoichiometryEntry> parse_side(std::string_view side, std::string_view text) {
  std::vector<StoichiometryEntry> out;
  const std::string whole = trim(side);
  if (whole.empty() || whole == "0" || whole == "\xE2\x88\x85") return out;  // U+2205
  std::size_t start = 0;
  while (start <= whole.size()) {
    std::size_t plus = whole.find('+', start);
    if (plus == std::string::npos) plus = whole.size();
    const std::string term = trim(std::string_view(whole).substr(start, plus - start));
    start = plus + 1;
    std::size_t k = 0;
    while (k < term.size() && std::isdigit(static_cast<unsigned char>(term[k]))) ++k;
    const std::string name = trim(std::string_view(term).substr(k));
    std::uint32_t count = 1;
    if (k > 0) {
      const unsigned long parsed = std::stoul(term.substr(0, k));
      if (parsed < 1 || parsed > 1000) {
        throw InvalidArgument("in '" + std::string(text) + "': coefficient of '" + name +
                              "' must be a whole number >= 1");
      }
      count = static_cast<std::uint32_t>(parsed);
    }
    if (!identifier(name)) {
      throw InvalidArgument("in '" + std::string(text) + "': '" + term +
                            "' is not a species term; allowed: [coefficient] name, names like "
                            "[A-Za-z_][A-Za-z0-9_]*, terms joined by '+', '0' for no species");
    }
    bool merged = false;
    for (auto& e : out) {
      if (e.species == name) {
        e.count += count;
        merged = true;
      }
    }
    if (!merged) out.push_back({name, count});
    if (plus == whole.size()) break;
  }
  return out;
}

}  // namespace

ReactionEquation parse_reaction_equation(std::string_view text) {
  ReactionEquation eq;
  std::size_t arrow = text.find("<->");
  std::size_t arrow_len = 3;
  if (arrow != std::string_view::npos) {
    eq.reversible = true;
  } else {
    arrow = text.find("->");
    arrow_len = 2;
  }
  if (arrow == std::string_view::npos) {
    throw InvalidArgument("'" + std::string(text) +
                          "' has no arrow; allowed: 'reactants -> products' or "
                          "'reactants <-> products' (e.g. 'A + B -> C')");
  }
  const std::string_view rest = text.substr(arrow + arrow_len);
  if (rest.find("->") != std::string_view::npos) {
    throw InvalidArgument("'" + std::string(text) + "' has more than one arrow");
  }
  eq.reactants = parse_side(text.substr(0, arrow), text);
  eq.products = parse_side(rest, text);
  if (eq.reactants.empty() && eq.products.empty()) {
    throw InvalidArgument("'" + std::string(text) + "' names no species on either side");
  }
  return eq;
}

}  // namespace sadr::orchestrator
