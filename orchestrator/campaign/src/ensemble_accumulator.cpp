// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/ensemble_accumulator.hpp"

#include <cmath>
#include <limits>

#include "sadr/common/status.hpp"
#include "sadr/orchestrator/atomic_file.hpp"
#include "sadr/orchestrator/frame_writers.hpp"

namespace sadr::orchestrator {

EnsembleAccumulator::EnsembleAccumulator(std::vector<std::string> species,
                                         std::size_t particle_count)
    : species_(std::move(species)), n_(particle_count) {}

EnsembleAccumulator::Frame& EnsembleAccumulator::frame_at(std::size_t frame, double time) {
  if (frame >= frames_.size()) frames_.resize(frame + 1);
  Frame& f = frames_[frame];
  if (f.count == 0) {
    f.time = time;
    f.mean.assign(species_.size() * n_, 0.0);
    f.m2.assign(species_.size() * n_, 0.0);
  } else if (f.time != time) {
    throw InvalidArgument("ensemble: frame " + std::to_string(frame) + " has time " +
                          format_value(f.time) + " but a realization reported " +
                          format_value(time) + "; realizations must share output times");
  }
  return f;
}

void EnsembleAccumulator::add(std::size_t frame, double time,
                              std::span<const SpeciesColumn> columns) {
  std::vector<const std::vector<double>*> values(species_.size(), nullptr);
  for (std::size_t s = 0; s < species_.size(); ++s) {
    for (const auto& c : columns) {
      if (c.name == species_[s]) values[s] = &c.values;
    }
    if (!values[s]) {
      throw InvalidArgument("ensemble: species '" + species_[s] + "' missing from frame " +
                            std::to_string(frame));
    }
    if (values[s]->size() != n_) {
      throw InvalidArgument("ensemble: species '" + species_[s] + "' has " +
                            std::to_string(values[s]->size()) + " values, expected " +
                            std::to_string(n_));
    }
  }
  Frame& f = frame_at(frame, time);
  f.count += 1;
  const double n = static_cast<double>(f.count);
  for (std::size_t s = 0; s < species_.size(); ++s) {
    for (std::size_t i = 0; i < n_; ++i) {
      const double x = (*values[s])[i];
      double& mean = f.mean[s * n_ + i];
      const double delta = x - mean;
      mean += delta / n;
      f.m2[s * n_ + i] += delta * (x - mean);
    }
  }
}

void EnsembleAccumulator::merge(const EnsembleAccumulator& other) {
  if (other.species_ != species_ || other.n_ != n_) {
    throw InvalidArgument("ensemble: cannot merge accumulators over different species or N");
  }
  for (std::size_t k = 0; k < other.frames_.size(); ++k) {
    const Frame& b = other.frames_[k];
    if (b.count == 0) continue;
    Frame& a = frame_at(k, b.time);
    if (a.count == 0) {
      a = b;
      continue;
    }
    const double na = static_cast<double>(a.count);
    const double nb = static_cast<double>(b.count);
    const double nt = na + nb;
    for (std::size_t j = 0; j < a.mean.size(); ++j) {
      const double delta = b.mean[j] - a.mean[j];
      a.mean[j] += delta * nb / nt;
      a.m2[j] += b.m2[j] + delta * delta * na * nb / nt;
    }
    a.count += b.count;
  }
}

std::size_t EnsembleAccumulator::realizations(std::size_t frame) const {
  return frame < frames_.size() ? frames_[frame].count : 0;
}

double EnsembleAccumulator::mean(std::size_t frame, std::size_t species,
                                 std::size_t particle) const {
  return frames_.at(frame).mean.at(species * n_ + particle);
}

double EnsembleAccumulator::variance(std::size_t frame, std::size_t species,
                                     std::size_t particle) const {
  const Frame& f = frames_.at(frame);
  if (f.count < 2) return std::numeric_limits<double>::quiet_NaN();
  return f.m2.at(species * n_ + particle) / static_cast<double>(f.count - 1);
}

void EnsembleAccumulator::write_csv(std::size_t frame, const std::filesystem::path& path,
                                    std::span<const std::uint64_t> ids) const {
  const Frame& f = frames_.at(frame);
  std::string x = "time,id,realizations";
  for (const auto& s : species_) {
    x.push_back(',');
    x.append(s).append("_mean,").append(s).append("_var");
  }
  x += '\n';
  for (std::size_t i = 0; i < n_; ++i) {
    append_number(x, f.time);
    x.push_back(',');
    append_integer(x, ids.size() == n_ ? ids[i] : i);
    x.push_back(',');
    append_integer(x, f.count);
    for (std::size_t s = 0; s < species_.size(); ++s) {
      x.push_back(',');
      append_number(x, mean(frame, s, i));
      x.push_back(',');
      append_number(x, variance(frame, s, i));
    }
    x += '\n';
  }
  write_file_atomic(path, x);
}

}  // namespace sadr::orchestrator
