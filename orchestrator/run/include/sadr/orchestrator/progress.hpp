// SPDX-License-Identifier: MIT
/// \file progress.hpp
/// Progress of a long run on stderr: a bar with ETA on a terminal, plain
/// lines every ~10 % (and at most every 5 s) otherwise.
#pragma once

#include <chrono>
#include <string>

namespace sadr::orchestrator {

class Progress {
 public:
  /// @param end_time simulated end time [time]; @param label line prefix
  Progress(double start_time, double end_time, std::string label, bool enabled);
  /// Reports that simulated time `t` was reached after `steps` coupling steps.
  void update(double t, std::uint64_t steps);
  /// Ends the bar line (terminal) and prints a summary line.
  void finish(double t, std::uint64_t steps);

 private:
  double start_, end_;
  std::string label_;
  bool enabled_, tty_;
  std::chrono::steady_clock::time_point t0_, last_;
  double last_fraction_ = -1.0;
};

}  // namespace sadr::orchestrator
