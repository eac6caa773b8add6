// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace sadr::orchestrator {
namespace {
std::string hms(double seconds) {
  if (!(seconds >= 0) || seconds > 1e7) return "--:--:--";
  const long s = static_cast<long>(seconds + 0.5);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%02ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  return buf;
}
}  // namespace

Progress::Progress(double start_time, double end_time, std::string label, bool enabled)
    : start_(start_time),
      end_(end_time),
      label_(std::move(label)),
      enabled_(enabled),
      tty_(isatty(STDERR_FILENO) != 0),
      t0_(std::chrono::steady_clock::now()),
      last_(t0_) {}

void Progress::update(double t, std::uint64_t steps) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  const double span = end_ - start_;
  const double frac = span > 0 ? std::clamp((t - start_) / span, 0.0, 1.0) : 1.0;
  const double elapsed = std::chrono::duration<double>(now - t0_).count();
  const double since = std::chrono::duration<double>(now - last_).count();
  const double eta = frac > 0 ? elapsed * (1 - frac) / frac : -1;
  if (tty_) {
    if (since < 0.1 && frac < 1.0) return;
    constexpr int kWidth = 30;
    const int fill = static_cast<int>(frac * kWidth);
    std::fprintf(stderr, "\r%s[%.*s%*s] %5.1f%%  t = %-11.5g step %-8llu elapsed %s  ETA %s",
                 label_.c_str(), fill, "##############################", kWidth - fill, "",
                 100 * frac, t, static_cast<unsigned long long>(steps), hms(elapsed).c_str(),
                 hms(eta).c_str());
  } else {
    if (frac - last_fraction_ < 0.1 && since < 5.0 && frac < 1.0) return;
    std::fprintf(stderr, "%sprogress %5.1f%%  t = %.6g  step %llu  elapsed %s  ETA %s\n",
                 label_.c_str(), 100 * frac, t, static_cast<unsigned long long>(steps),
                 hms(elapsed).c_str(), hms(eta).c_str());
    last_fraction_ = frac;
  }
  std::fflush(stderr);
  last_ = now;
}

void Progress::finish(double t, std::uint64_t steps) {
  if (!enabled_) return;
  if (last_fraction_ < 1.0 || tty_) update(t, steps);
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
  std::fprintf(stderr, "%s%sreached t = %.6g after %llu coupling steps in %s\n", tty_ ? "\n" : "",
               label_.c_str(), t, static_cast<unsigned long long>(steps), hms(elapsed).c_str());
  std::fflush(stderr);
}

}  // namespace sadr::orchestrator
