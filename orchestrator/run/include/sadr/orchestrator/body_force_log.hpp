// SPDX-License-Identifier: MIT
/// \file body_force_log.hpp
/// The time series of the forces on bodies (scene fluid.body_forces): body_forces.csv beside the
/// frames, one row per fluid stage and body, and its summary for run.json (docs/running.md).
#pragma once

#include <array>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sadr/orchestrator/service_interfaces.hpp"

namespace sadr::orchestrator {

class BodyForceLog {
 public:
  /// `dir`/body_forces.csv with its header. With resume_time >= 0 (a resumed run) the rows of
  /// the file up to that time are kept (and counted in the summary), later ones dropped.
  BodyForceLog(const std::filesystem::path& dir, double t_end, double resume_time = -1.0);
  /// One fluid stage [t - dt, t]: a row per body.
  void add(double t, double dt, const std::vector<BodyForceSample>& forces);
  /// {body: {"time", "force", "torque", "reference" (the last stage), "mean_force",
  /// "mean_torque", "mean_from", "mean_to" (time-weighted over the stages ending in the second
  /// half of the run, t > t_end / 2)}}; {} before the first stage.
  [[nodiscard]] nlohmann::json summary() const;
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  struct Totals {
    double t = 0;
    std::array<double, 3> force{}, torque{}, reference{};
    std::array<double, 6> weighted{};  ///< sum of dt (force, torque) over the second half
    double weight = 0, from = -1, to = 0;
  };
  void note(const std::string& name, double t, double dt, const std::array<double, 3>& force,
            const std::array<double, 3>& torque, const std::array<double, 3>* reference);

  std::filesystem::path path_;
  double half_ = 0;
  std::ofstream out_;
  std::vector<std::string> order_;
  std::map<std::string, Totals> totals_;
};

}  // namespace sadr::orchestrator
