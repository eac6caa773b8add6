// SPDX-License-Identifier: MIT
#include "sadr/model/problems.hpp"

#include <cmath>

#include "sadr/common/status.hpp"

namespace sadr::model {

std::string Problem::message() const {
  if (value.empty()) return field + ": " + allowed;
  return field + " = " + value + " (allowed: " + allowed + ")";
}

std::string Problems::path(std::string_view field) const {
  if (prefix_.empty()) return std::string(field);
  if (field.empty()) return prefix_;
  return prefix_ + (field.front() == '[' ? "" : ".") + std::string(field);
}

void Problems::add(std::string_view field, std::string value, std::string allowed) {
  list_.push_back(Problem{path(field), std::move(value), std::move(allowed)});
}

void Problems::add(std::string_view field, double value, std::string allowed) {
  add(field, format_value(value), std::move(allowed));
}

void Problems::add_text(std::string_view field, std::string message) {
  list_.push_back(Problem{path(field), "", std::move(message)});
}

void Problems::finite_nonneg(std::string_view field, double value) {
  if (!(std::isfinite(value) && value >= 0)) add(field, value, "finite and >= 0");
}

void Problems::finite_positive(std::string_view field, double value) {
  if (!(std::isfinite(value) && value > 0)) add(field, value, "finite and > 0");
}

std::string Problems::text() const {
  std::string out;
  for (const auto& p : list_) out += (out.empty() ? "" : "; ") + p.message();
  return out;
}

void Problems::throw_if_any(std::string_view context) const {
  if (list_.empty()) return;
  std::vector<std::pair<std::string, std::string>> details;
  details.reserve(list_.size());
  for (const auto& p : list_) details.emplace_back(p.field, p.value.empty() ? p.allowed : p.value);
  std::string message = context.empty() ? text() : std::string(context) + ": " + text();
  throw InvalidArgument(message, std::move(details));
}

}  // namespace sadr::model
