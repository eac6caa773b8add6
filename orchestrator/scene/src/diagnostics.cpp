// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/diagnostics.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <utility>

#include "sadr/common/status.hpp"

namespace sadr::orchestrator {

void Diagnostics::add_override(std::string resolved_path, std::string text) {
  overrides_.emplace_back(std::move(resolved_path), std::move(text));
}

std::string Diagnostics::override_of(std::string_view field) const {
  std::string found;
  for (const auto& [path, text] : overrides_) {  // the last one wins, as when applied
    const bool under = field.size() > path.size() && field.substr(0, path.size()) == path &&
                       (field[path.size()] == '.' || field[path.size()] == '[');
    if (field == path || under) found = text;
  }
  return found;
}

std::string Diagnostics::format(SourceLocation& where, std::string_view field,
                                std::string_view message) const {
  const std::string set_by = field.empty() ? std::string() : override_of(field);
  if (!set_by.empty()) where = {};  // the value is not in the file
  std::string line = file_;
  if (where.line > 0) {
    line.push_back(':');
    line.append(std::to_string(where.line));
    line.push_back(':');
    line.append(std::to_string(where.column));
  }
  line.append(": ");
  if (!field.empty()) {
    line.append(field);
    line += ": ";
  }
  line.append(message);
  if (!set_by.empty()) line += " (set by --set " + set_by + ")";
  return line;
}

void Diagnostics::error(SourceLocation where, std::string_view field, std::string_view message) {
  messages_.push_back(format(where, field, message));
  where_.push_back(where);
}

void Diagnostics::warning(SourceLocation where, std::string_view field, std::string_view message) {
  warnings_.push_back(format(where, field, message));
  warning_where_.push_back(where);
}

namespace {

/// The indices of `where` in file order (positions first, then the ones without).
std::vector<std::size_t> file_order(const std::vector<SourceLocation>& where) {
  std::vector<std::size_t> order(where.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  auto key = [&](std::size_t i) {
    const SourceLocation w = where[i];
    return std::pair<long, long>(w.line > 0 ? w.line : std::numeric_limits<long>::max(), w.column);
  };
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
  return order;
}

}  // namespace

std::vector<std::string> Diagnostics::warnings() const {
  std::vector<std::string> out;
  for (const std::size_t i : file_order(warning_where_)) out.push_back(warnings_[i]);
  return out;
}

void Diagnostics::throw_if_any() const {
  if (messages_.empty()) return;
  std::string text = "invalid scene '" + file_ + "': " + std::to_string(messages_.size()) +
                     (messages_.size() == 1 ? " problem" : " problems");
  std::vector<std::pair<std::string, std::string>> details;
  for (const std::size_t i : file_order(where_)) {
    text += "\n  " + messages_[i];
    details.emplace_back("problem", messages_[i]);
  }
  throw InvalidArgument(text, std::move(details));
}

std::size_t levenshtein(std::string_view a, std::string_view b) {
  std::vector<std::size_t> prev(b.size() + 1);
  std::vector<std::size_t> cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t subst = prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, subst});
    }
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

namespace {
// Names people reach for from the papers or other codes, mapped to our keys.
// The enumerated values too (region shapes, ...): a synonym applies only where its target is
// one of the allowed names.
constexpr std::array<std::pair<std::string_view, std::string_view>, 22> kSynonyms{{
    {"kappa", "diffusivity"},
    {"D", "diffusivity"},
    {"h", "smoothing_length"},
    {"tau", "coupling_step"},
    {"dt", "coupling_step"},
    {"t_end", "end"},
    {"end_time", "end"},
    {"viscosity", "shear_viscosity"},
    {"eta", "shear_viscosity"},
    {"kT", "temperature"},
    {"rho0", "reference_density"},
    {"c0", "sound_speed"},
    {"circle", "disk"},
    {"disc", "disk"},
    {"ball", "sphere"},
    {"rectangle", "box"},
    {"square", "box"},
    {"cube", "box"},
    {"cuboid", "box"},
    {"ring", "annulus"},
    {"slab", "channel"},
    {"stripe", "channel"},
}};
}  // namespace

std::optional<std::string> nearest_name(std::string_view word,
                                        std::span<const std::string_view> candidates) {
  for (const auto& [alias, key] : kSynonyms) {
    if (alias == word && std::find(candidates.begin(), candidates.end(), key) != candidates.end()) {
      return std::string(key);
    }
  }
  std::optional<std::string> best;
  std::size_t best_distance = std::max<std::size_t>(2, word.size() / 3) + 1;
  for (const auto& c : candidates) {
    const std::size_t d = levenshtein(word, c);
    if (d < best_distance) {
      best_distance = d;
      best = std::string(c);
    }
  }
  return best;
}

std::string join_names(std::span<const std::string_view> names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) out += ", ";
    out.append(names[i]);
  }
  return out;
}

std::string format_number(double value) {
  char buf[64];
  for (int precision = 6; precision <= 17; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, value);
    if (std::strtod(buf, nullptr) == value) break;
  }
  return buf;
}

}  // namespace sadr::orchestrator
