// SPDX-License-Identifier: MIT
/// \file log.hpp
/// Minimal leveled logging to stderr: "[time] [level] [component] message".
/// Level from the environment variable SADR_LOG_LEVEL (error|warn|info|debug;
/// default info) or set_level(). Thread safe (one line per call).
#pragma once

#include <sstream>
#include <string>
#include <string_view>

namespace sadr::log {

enum class Level : int { kError = 0, kWarn = 1, kInfo = 2, kDebug = 3 };

void set_level(Level level);
Level level();
/// Sets the component name printed in every line of this process ("fluid", "ssa", ...).
void set_component(std::string_view component);
void write(Level level, std::string_view message);

template <typename... Args>
void emit(Level lv, const Args&... args) {
  if (static_cast<int>(lv) > static_cast<int>(level())) return;
  std::ostringstream out;
  (out << ... << args);
  write(lv, out.str());
}
template <typename... Args>
void error(const Args&... a) {
  emit(Level::kError, a...);
}
template <typename... Args>
void warn(const Args&... a) {
  emit(Level::kWarn, a...);
}
template <typename... Args>
void info(const Args&... a) {
  emit(Level::kInfo, a...);
}
template <typename... Args>
void debug(const Args&... a) {
  emit(Level::kDebug, a...);
}

}  // namespace sadr::log
