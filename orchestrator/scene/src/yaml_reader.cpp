// SPDX-License-Identifier: MIT
#include "yaml_reader.hpp"

#include <charconv>
#include <cmath>
#include <set>

namespace sadr::orchestrator::detail {

namespace {
std::string quoted(const YAML::Node& node) {
  if (node.IsScalar()) return "'" + node.Scalar() + "'";
  if (node.IsSequence()) return "a list";
  if (node.IsMap()) return "a map";
  return "nothing";
}
}  // namespace

std::string allowed_text(Bound bound, std::string_view unit) {
  std::string s = "a number";
  if (bound == Bound::kPositive) s += " > 0";
  if (bound == Bound::kNonNegative) s += " >= 0";
  if (!unit.empty()) {
    s += " [";
    s.append(unit);
    s += "]";
  }
  return s;
}

SourceLocation YamlReader::location(const YAML::Node& node) {
  if (!node.IsDefined()) return {};
  const YAML::Mark m = node.Mark();
  if (m.line < 0) return {};
  return {m.line + 1, m.column + 1};
}

Field YamlReader::child(const Field& parent, std::string_view key) {
  Field f;
  // Const lookup: the non-const operator[] would insert the key into the document.
  if (parent.node.IsMap()) {
    const YAML::Node& map = parent.node;
    const YAML::Node value = map[std::string(key)];
    if (value.IsDefined()) f.node = value;
  }
  f.path = parent.path.empty() ? std::string(key) : parent.path + "." + std::string(key);
  const SourceLocation here = f.node.IsDefined() ? location(f.node) : SourceLocation{};
  f.where = here.line > 0 ? here : parent.where;
  return f;
}

Field YamlReader::element(const Field& parent, std::size_t i) {
  Field f;
  const YAML::Node& seq = parent.node;
  f.node = seq[i];
  f.path = parent.path + "[" + std::to_string(i) + "]";
  const SourceLocation here = location(f.node);
  f.where = here.line > 0 ? here : parent.where;
  return f;
}

Field YamlReader::resolve(const Field& object, std::string_view path) {
  Field at = object;
  std::size_t i = 0;
  while (i < path.size()) {
    Field next;
    if (path[i] == '[') {
      const std::size_t close = path.find(']', i);
      if (close == std::string_view::npos || !at.node.IsSequence()) break;
      std::size_t k = 0;
      for (std::size_t c = i + 1; c < close; ++c)
        k = 10 * k + static_cast<std::size_t>(path[c] - '0');
      if (k >= at.node.size()) break;
      next = element(at, k);
      i = close + 1;
    } else {
      if (path[i] == '.') ++i;
      const std::size_t end = path.find_first_of(".[", i);
      const std::string_view key = path.substr(i, end - i);
      next = child(at, key);
      if (!present(next)) break;
      i = end == std::string_view::npos ? path.size() : end;
    }
    at = next;
  }
  return at;
}

void YamlReader::report(const Field& object, const model::Problems& problems,
                        std::span<const std::pair<std::string_view, std::string_view>> units,
                        std::span<const std::pair<std::string_view, Field>> aliases) {
  for (const model::Problem& p : problems.list()) {
    const Field* alias = nullptr;
    for (const auto& [prefix, field] : aliases) {
      if (p.field.starts_with(prefix)) alias = &field;
    }
    const Field at = alias ? *alias : resolve(object, p.field);
    const std::string path = alias                    ? alias->path
                             : p.field.empty()        ? object.path
                             : object.path.empty()    ? p.field
                             : p.field.front() == '[' ? object.path + p.field
                                                      : object.path + "." + p.field;
    if (p.value.empty()) {
      diag_.error(at.where, path, p.allowed);
      continue;
    }
    std::string allowed = p.allowed;
    for (const auto& [field, unit] : units) {
      if (field == p.field) allowed += " [" + std::string(unit) + "]";
    }
    diag_.error(at.where, path, p.value + " is out of range; allowed: " + allowed);
  }
}

bool YamlReader::expect_map(const Field& f, std::span<const std::string_view> allowed) {
  if (!f.node.IsMap()) {
    error(f, "expected a map with keys (" + join_names(allowed) + "), got " + quoted(f.node));
    return false;
  }
  std::set<std::string> seen;
  for (const auto& kv : f.node) {
    const std::string key = kv.first.Scalar();
    const SourceLocation where = location(kv.first);
    const std::string context = f.path.empty() ? "the scene" : f.path;
    if (!seen.insert(key).second) {
      diag_.error(where, "", "duplicate key '" + key + "' in " + context);
      continue;
    }
    bool known = false;
    for (const auto& a : allowed) known = known || a == key;
    if (known) continue;
    std::string msg = "unknown key '" + key + "' in " + context;
    if (auto near = nearest_name(key, allowed)) msg += "; did you mean '" + *near + "'?";
    msg += " (allowed: " + join_names(allowed) + ")";
    const std::string set_by = diag_.override_of(f.path.empty() ? key : f.path + "." + key);
    if (set_by.empty()) {
      diag_.error(where, "", msg);
    } else {
      diag_.error({}, "", msg + " (set by --set " + set_by + ")");
    }
  }
  return true;
}

bool YamlReader::expect_sequence(const Field& f) {
  if (!present(f)) return false;
  if (!f.node.IsSequence()) {
    error(f, "expected a list, got " + quoted(f.node));
    return false;
  }
  return true;
}

std::optional<double> YamlReader::number_at(const Field& f, Bound bound, std::string_view unit) {
  if (!f.node.IsScalar()) {
    error(f, "expected " + allowed_text(bound, unit) + ", got " + quoted(f.node));
    return std::nullopt;
  }
  const std::string& text = f.node.Scalar();
  double value = 0.0;
  // from_chars rejects "1.0abc", leading '+' and YAML's ".inf"/".nan" (not finite anyway).
  const char* first = text.data();
  const char* last = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(first, last, value);
  if (ec != std::errc() || ptr != last) {
    error(f, "'" + text + "' is not a number; allowed: " + allowed_text(bound, unit));
    return std::nullopt;
  }
  const bool ok = std::isfinite(value) && (bound != Bound::kPositive || value > 0.0) &&
                  (bound != Bound::kNonNegative || value >= 0.0);
  if (!ok) {
    error(f, text + " is out of range; allowed: " + allowed_text(bound, unit));
    return std::nullopt;
  }
  return value;
}

std::optional<double> YamlReader::number(const Field& parent, std::string_view key, Bound bound,
                                         std::string_view unit, bool required) {
  const Field f = child(parent, key);
  if (!present(f)) {
    if (required) error(f, "missing; required: " + allowed_text(bound, unit));
    return std::nullopt;
  }
  return number_at(f, bound, unit);
}

double YamlReader::number_or(const Field& parent, std::string_view key, double fallback,
                             Bound bound, std::string_view unit) {
  return number(parent, key, bound, unit, false).value_or(fallback);
}

std::optional<std::uint64_t> YamlReader::integer(const Field& parent, std::string_view key,
                                                 std::uint64_t lo, std::uint64_t hi,
                                                 bool required) {
  const Field f = child(parent, key);
  const std::string allowed =
      "a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  if (!present(f)) {
    if (required) error(f, "missing; required: " + allowed);
    return std::nullopt;
  }
  if (!f.node.IsScalar()) {
    error(f, "expected " + allowed + ", got " + quoted(f.node));
    return std::nullopt;
  }
  const std::string& text = f.node.Scalar();
  std::uint64_t value = 0;
  auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || ptr != text.data() + text.size() || value < lo || value > hi) {
    error(f, "'" + text + "' is not allowed; allowed: " + allowed);
    return std::nullopt;
  }
  return value;
}

std::optional<std::string> YamlReader::string(const Field& parent, std::string_view key,
                                              bool required) {
  const Field f = child(parent, key);
  if (!present(f)) {
    if (required) error(f, "missing; required: a text value");
    return std::nullopt;
  }
  if (!f.node.IsScalar()) {
    error(f, "expected a text value, got " + quoted(f.node));
    return std::nullopt;
  }
  return f.node.Scalar();
}

std::optional<std::string> YamlReader::choice(const Field& parent, std::string_view key,
                                              std::span<const std::string_view> allowed,
                                              bool required, std::string_view what) {
  const Field f = child(parent, key);
  auto s = string(parent, key, required);
  if (!s) {
    if (!present(f) && required) return std::nullopt;
    return std::nullopt;
  }
  for (const auto& a : allowed) {
    if (a == *s) return s;
  }
  std::string msg = "unknown " + std::string(what) + " '" + *s + "'";
  if (auto near = nearest_name(*s, allowed)) msg += "; did you mean '" + *near + "'?";
  msg += " (allowed: " + join_names(allowed) + ")";
  error(f, msg);
  return std::nullopt;
}

std::optional<bool> YamlReader::boolean(const Field& parent, std::string_view key, bool required) {
  const Field f = child(parent, key);
  if (!present(f)) {
    if (required) error(f, "missing; required: true or false");
    return std::nullopt;
  }
  if (f.node.IsScalar()) {
    const std::string& t = f.node.Scalar();
    if (t == "true" || t == "True" || t == "yes" || t == "on") return true;
    if (t == "false" || t == "False" || t == "no" || t == "off") return false;
  }
  error(f, quoted(f.node) + " is not allowed; allowed: true or false");
  return std::nullopt;
}

std::optional<std::array<double, 3>> YamlReader::vector(const Field& parent, std::string_view key,
                                                        int n, std::string_view unit,
                                                        bool required) {
  const Field f = child(parent, key);
  const std::string allowed = "a list of " + std::to_string(n) + " numbers [" + std::string(unit) +
                              "] (one per axis of the scene's dimension)";
  if (!present(f)) {
    if (required) error(f, "missing; required: " + allowed);
    return std::nullopt;
  }
  if (!f.node.IsSequence() || f.node.size() != static_cast<std::size_t>(n)) {
    const std::string got =
        f.node.IsSequence() ? "a list of " + std::to_string(f.node.size()) : quoted(f.node);
    error(f, "expected " + allowed + ", got " + got);
    return std::nullopt;
  }
  std::array<double, 3> out{};
  bool ok = true;
  for (int a = 0; a < n; ++a) {
    auto v = number_at(element(f, static_cast<std::size_t>(a)), Bound::kAny, unit);
    if (v) {
      out[static_cast<std::size_t>(a)] = *v;
    } else {
      ok = false;
    }
  }
  if (!ok) return std::nullopt;
  return out;
}

std::optional<std::vector<std::string>> YamlReader::string_list(const Field& parent,
                                                                std::string_view key,
                                                                bool required) {
  const Field f = child(parent, key);
  if (!present(f)) {
    if (required) error(f, "missing; required: a list of names");
    return std::nullopt;
  }
  if (f.node.IsScalar()) return std::vector<std::string>{f.node.Scalar()};
  if (!f.node.IsSequence()) {
    error(f, "expected a list of names, got " + quoted(f.node));
    return std::nullopt;
  }
  std::vector<std::string> out;
  for (std::size_t i = 0; i < f.node.size(); ++i) {
    const Field e = element(f, i);
    if (!e.node.IsScalar()) {
      error(e, "expected a name, got " + quoted(e.node));
      continue;
    }
    out.push_back(e.node.Scalar());
  }
  return out;
}

}  // namespace sadr::orchestrator::detail
