// SPDX-License-Identifier: MIT
/// \file scoped_timer.hpp
/// Adds the wall-clock time of a scope to a run manifest's timings.
#pragma once

#include <chrono>
#include <map>
#include <string>

namespace sadr::orchestrator {

using Clock = std::chrono::steady_clock;

/// Adds the wall-clock time of its scope to timings[key] [s].
class ScopedTimer {
 public:
  ScopedTimer(std::map<std::string, double>& timings, const char* key)
      : timings_(timings), key_(key), t0_(Clock::now()) {}
  ~ScopedTimer() { timings_[key_] += std::chrono::duration<double>(Clock::now() - t0_).count(); }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;

 private:
  std::map<std::string, double>& timings_;
  const char* key_;
  Clock::time_point t0_;
};

}  // namespace sadr::orchestrator
