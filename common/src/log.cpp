// SPDX-License-Identifier: MIT
#include "sadr/common/log.hpp"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <mutex>
#include <string>

namespace sadr::log {
namespace {

Level level_from_env() {
  const char* env = std::getenv("SADR_LOG_LEVEL");
  if (!env) return Level::kInfo;
  const std::string v(env);
  if (v == "error") return Level::kError;
  if (v == "warn") return Level::kWarn;
  if (v == "debug") return Level::kDebug;
  return Level::kInfo;
}

std::atomic<int>& level_ref() {
  static std::atomic<int> lv{static_cast<int>(level_from_env())};
  return lv;
}
std::mutex& io_mutex() {
  static std::mutex m;
  return m;
}
std::string& component_ref() {
  static std::string c = "sadr";
  return c;
}
constexpr const char* kNames[] = {"error", "warn", "info", "debug"};

}  // namespace

void set_level(Level lv) {
  level_ref().store(static_cast<int>(lv));
}
Level level() {
  return static_cast<Level>(level_ref().load());
}
void set_component(std::string_view component) {
  std::lock_guard lock(io_mutex());
  component_ref() = std::string(component);
}

void write(Level lv, std::string_view message) {
  const auto now = std::chrono::system_clock::now();
  const std::time_t t = std::chrono::system_clock::to_time_t(now);
  const auto ms =
      std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
  std::tm tm{};
  gmtime_r(&t, &tm);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%H:%M:%S", &tm);
  std::lock_guard lock(io_mutex());
  std::fprintf(stderr, "[%s.%03d] [%s] [%s] %.*s\n", stamp, static_cast<int>(ms),
               kNames[static_cast<int>(lv)], component_ref().c_str(),
               static_cast<int>(message.size()), message.data());
  std::fflush(stderr);
}

}  // namespace sadr::log
