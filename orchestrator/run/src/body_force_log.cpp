// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/body_force_log.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "sadr/common/status.hpp"

namespace sadr::orchestrator {
namespace {

constexpr const char* kHeader = "t,dt,body,Fx,Fy,Fz,Tx,Ty,Tz";

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

/// The rows of an earlier body_forces.csv (a resumed run), as text lines.
std::vector<std::string> earlier_rows(const std::filesystem::path& path) {
  std::vector<std::string> rows;
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line) || line != kHeader) return rows;
  while (std::getline(in, line)) {
    if (!line.empty()) rows.push_back(line);
  }
  return rows;
}

}  // namespace

BodyForceLog::BodyForceLog(const std::filesystem::path& dir, double t_end, double resume_time)
    : path_(dir / "body_forces.csv"), half_(0.5 * t_end) {
  std::vector<std::string> kept;
  if (resume_time >= 0) {
    for (const auto& row : earlier_rows(path_)) {
      std::istringstream s(row);
      std::string cell;
      std::vector<std::string> cells;
      while (std::getline(s, cell, ',')) cells.push_back(cell);
      if (cells.size() != 9) continue;
      const double t = std::stod(cells[0]);
      if (t > resume_time * (1 + 1e-12) + 1e-300) continue;
      std::array<double, 3> f{}, tq{};
      for (std::size_t a = 0; a < 3; ++a) {
        f[a] = std::stod(cells[3 + a]);
        tq[a] = std::stod(cells[6 + a]);
      }
      note(cells[2], t, std::stod(cells[1]), f, tq, nullptr);
      kept.push_back(row);
    }
  }
  out_.open(path_, std::ios::trunc);
  if (!out_) throw Error(StatusCode::kInternal, "cannot write " + path_.string());
  out_ << kHeader << '\n';
  for (const auto& row : kept) out_ << row << '\n';
  out_.flush();
}

void BodyForceLog::note(const std::string& name, double t, double dt,
                        const std::array<double, 3>& force, const std::array<double, 3>& torque,
                        const std::array<double, 3>* reference) {
  if (std::find(order_.begin(), order_.end(), name) == order_.end()) order_.push_back(name);
  Totals& x = totals_[name];
  x.t = t;
  x.force = force;
  x.torque = torque;
  if (reference) x.reference = *reference;
  if (t > half_) {
    for (std::size_t a = 0; a < 3; ++a) {
      x.weighted[a] += dt * force[a];
      x.weighted[3 + a] += dt * torque[a];
    }
    if (x.from < 0) x.from = t - dt;
    x.weight += dt;
    x.to = t;
  }
}

void BodyForceLog::add(double t, double dt, const std::vector<BodyForceSample>& forces) {
  for (const auto& f : forces) {
    out_ << number(t) << ',' << number(dt) << ',' << f.name;
    for (double v : f.force) out_ << ',' << number(v);
    for (double v : f.torque) out_ << ',' << number(v);
    out_ << '\n';
    note(f.name, t, dt, f.force, f.torque, &f.reference);
  }
  out_.flush();
}

nlohmann::json BodyForceLog::summary() const {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& name : order_) {
    const Totals& x = totals_.at(name);
    nlohmann::json b = {
        {"time", x.t}, {"force", x.force}, {"torque", x.torque}, {"reference", x.reference}};
    if (x.weight > 0) {
      std::array<double, 3> f{}, tq{};
      for (std::size_t a = 0; a < 3; ++a) {
        f[a] = x.weighted[a] / x.weight;
        tq[a] = x.weighted[3 + a] / x.weight;
      }
      b["mean_force"] = f;
      b["mean_torque"] = tq;
      b["mean_from"] = x.from;
      b["mean_to"] = x.to;
    }
    out[name] = b;
  }
  return out;
}

}  // namespace sadr::orchestrator
