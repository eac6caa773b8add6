// SPDX-License-Identifier: MIT
/// \file bench_util.hpp
/// Timing, memory and JSON helpers for the ssa benchmarks.
#pragma once

#include <sys/resource.h>
#include <time.h>

#include <cstdio>
#include <map>
#include <string>
#include <variant>
#include <vector>

namespace sadr::ssa::bench {

/// Thread CPU time [s] (CLOCK_THREAD_CPUTIME_ID).
inline double thread_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// Process CPU time [s] over all threads (CLOCK_PROCESS_CPUTIME_ID).
inline double process_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// Wall-clock time [s] (CLOCK_MONOTONIC).
inline double wall_s() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// Peak resident set size of the process [MiB] (getrusage).
inline double peak_rss_mib() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return static_cast<double>(ru.ru_maxrss) / 1024.0;
}

/// Flat JSON object builder (numbers and strings, insertion order kept).
class Json {
 public:
  void num(const std::string& k, double v) {
    char b[64];
    std::snprintf(b, sizeof b, "%.6g", v);
    items_.emplace_back(k, b);
  }
  void str(const std::string& k, const std::string& v) { items_.emplace_back(k, "\"" + v + "\""); }
  void raw(const std::string& k, const std::string& v) { items_.emplace_back(k, v); }
  [[nodiscard]] std::string dump() const {
    std::string s = "{";
    for (std::size_t i = 0; i < items_.size(); ++i) {
      s += (i ? ", " : "") + std::string("\"") + items_[i].first + "\": " + items_[i].second;
    }
    return s + "}";
  }

 private:
  std::vector<std::pair<std::string, std::string>> items_;
};

}  // namespace sadr::ssa::bench
