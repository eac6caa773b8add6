// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/sweep_aggregate.hpp"

#include <algorithm>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

#include "sadr/common/status.hpp"
#include "sadr/orchestrator/atomic_file.hpp"
#include "sadr/orchestrator/ensemble_accumulator.hpp"
#include "sadr/orchestrator/frame_writers.hpp"
#include "sadr/orchestrator/region.hpp"
#include "sadr/orchestrator/sweep_frames.hpp"

namespace sadr::orchestrator {
namespace fs = std::filesystem;

double t95(std::size_t n) {
  if (n < 2) return std::numeric_limits<double>::quiet_NaN();
  const boost::math::students_t dist(static_cast<double>(n - 1));
  return boost::math::quantile(dist, 0.975);
}

namespace {

constexpr std::array<const char*, 4> kFluid{"vx", "vy", "vz", "density"};

/// The species columns followed by vx, vy, vz, density.
std::vector<SpeciesColumn> columns_of(const CsvFrame& f) {
  std::vector<SpeciesColumn> c = f.species;
  const std::size_t n = f.particles.ids.size();
  for (std::size_t a = 0; a < 3; ++a) {
    SpeciesColumn v{kFluid[a], std::vector<double>(n)};
    for (std::size_t i = 0; i < n; ++i) v.values[i] = f.particles.velocities[3 * i + a];
    c.push_back(std::move(v));
  }
  c.push_back({"density", f.particles.densities});
  return c;
}

/// Appends "<prefix>,k,t,<name>,<total>" to `out`.
void tidy_row(std::ostream& out, const std::string& prefix, std::size_t k, double t,
              const std::string& name, double value) {
  std::string row = prefix + ',' + std::to_string(k) + ',';
  append_number(row, t);
  row += ',' + name + ',';
  append_number(row, value);
  out << row << '\n';
}

/// The named observables of one frame, as tidy rows.
void named_rows(std::ostream& out, const std::string& prefix, std::size_t k, CsvFrame& f,
                const NamedObservables& named, const fs::path& path) {
  const int saved = f.particles.dimension;
  f.particles.dimension = named.dimension;  // the file has 3 axes; regions use the scene's
  for (std::size_t o = 0; o < named.specs.size(); ++o) {
    const ObservableSpec& spec = named.specs[o];
    Region region = named.regions[o];
    resolve_membership(region, f.particles, named.tolerance);
    const auto col = std::find_if(f.species.begin(), f.species.end(),
                                  [&](const SpeciesColumn& c) { return c.name == spec.species; });
    if (col == f.species.end()) {
      throw InvalidArgument(path.string() + ": no column '" + spec.species + "' for observable '" +
                            spec.name + "'");
    }
    double sum = 0;
    for (const std::uint32_t i : region.particles) sum += col->values[i];
    if (spec.mean && region.particles.empty()) {
      throw InvalidArgument(path.string() + ": observable '" + spec.name + "': region '" +
                            spec.region +
                            "' holds no particle in this frame; a mean needs at least one");
    }
    tidy_row(out, prefix, k, f.time, spec.name,
             spec.mean ? sum / static_cast<double>(region.particles.size()) : sum);
  }
  f.particles.dimension = saved;
}

}  // namespace

NamedObservables named_observables(const Scene& scene) {
  NamedObservables n;
  n.dimension = scene.box.dimension;
  double extent = 0.0;
  for (int a = 0; a < scene.box.dimension; ++a) extent = std::max(extent, scene.box.length(a));
  n.tolerance = 1e-9 * std::max(extent, 1e-300);
  for (const auto& spec : scene.output.observables) {
    n.specs.push_back(spec);
    const Region* rg = scene.find_region(spec.region);
    Region all;
    all.name = "all";
    n.regions.push_back(rg ? *rg : all);  // "all" is not in scene.regions
  }
  return n;
}

PointAggregate aggregate_point(std::span<const fs::path> runs,
                               std::span<const std::string> prefixes, const fs::path& out,
                               const std::string& name, std::ostream& observables,
                               const NamedObservables& named) {
  if (runs.empty()) throw InvalidArgument("aggregate: no runs");
  PointAggregate result;
  std::optional<EnsembleAccumulator> acc;
  std::map<std::size_t, CsvFrame> first;  // realization 0's frames (positions for the .vtu)
  std::vector<std::string> species;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const auto frames = list_csv_frames(runs[r]);
    if (frames.empty()) {
      throw InvalidArgument(runs[r].string() +
                            ": no CSV frames (the scene's output.formats must include csv)");
    }
    if (r > 0) {
      for (const auto& [k, f] : first) {
        if (!frames.count(k)) {
          throw InvalidArgument(runs[r].string() + ": frame " + std::to_string(k) +
                                " is missing (" + runs[0].string() +
                                " has it); refusing to "
                                "average it over fewer realizations");
        }
      }
      for (const auto& [k, p] : frames) {
        if (!first.count(k)) {
          throw InvalidArgument(p.string() + ": frame " + std::to_string(k) + " is not in " +
                                runs[0].string());
        }
      }
    }
    for (const auto& [k, path] : frames) {
      CsvFrame f = read_frame_csv(path);
      if (!acc) {
        for (const auto& s : f.species) species.push_back(s.name);
        std::vector<std::string> all = species;
        all.insert(all.end(), kFluid.begin(), kFluid.end());
        acc.emplace(all, f.particles.ids.size());
      }
      if (r > 0) {
        const CsvFrame& f0 = first.at(k);
        if (f.particles.ids != f0.particles.ids) {
          throw InvalidArgument(path.string() + ": particle ids differ from " + runs[0].string() +
                                "'s frame " + std::to_string(k));
        }
        if (f.particles.positions != f0.particles.positions) result.positions_identical = false;
      }
      try {
        acc->add(k, f.time, columns_of(f));
      } catch (const Error& e) {
        throw InvalidArgument(path.string() + ": " + e.what());
      }
      for (const auto& s : f.species) {
        double total = 0;
        for (double v : s.values) total += v;
        tidy_row(observables, prefixes[r], k, f.time, s.name, total);
      }
      named_rows(observables, prefixes[r], k, f, named, path);
      if (r == 0) first.emplace(k, std::move(f));
    }
  }
  result.realizations = runs.size();
  result.frames = first.size();
  // Velocity and density are aggregated where they differ between realizations.
  const std::size_t ns = species.size();
  for (const auto& [k, f] : first) {
    for (std::size_t c = ns; c < ns + kFluid.size() && runs.size() > 1; ++c) {
      for (std::size_t i = 0; i < f.particles.ids.size(); ++i) {
        if (acc->variance(k, c, i) > 0) result.fluid_columns = true;
      }
    }
  }
  if (!result.positions_identical) {
    result.notes.push_back(
        "positions differ between realizations; the .vtu files carry "
        "realization 0's positions");
  }
  ensure_directory(out);
  PvdCollection pvd(out / (name + ".pvd"));
  const std::size_t used = result.fluid_columns ? ns + kFluid.size() : ns;
  const double t = t95(runs.size());
  for (const auto& [k, f] : first) {
    const std::size_t n = f.particles.ids.size();
    std::vector<SpeciesColumn> stats;
    for (std::size_t c = 0; c < used; ++c) {
      const std::string& col = acc->species()[c];
      SpeciesColumn mean{col + "_mean", {}}, var{col + "_var", {}}, sem{col + "_sem", {}},
          lo{col + "_ci95_lo", {}}, hi{col + "_ci95_hi", {}};
      for (std::size_t i = 0; i < n; ++i) {
        const double m = acc->mean(k, c, i), v = acc->variance(k, c, i);
        const double se = std::sqrt(v / static_cast<double>(runs.size()));
        mean.values.push_back(m);
        var.values.push_back(v);
        sem.values.push_back(se);
        lo.values.push_back(m - t * se);
        hi.values.push_back(m + t * se);
      }
      for (auto* s : {&mean, &var, &sem, &lo, &hi}) stats.push_back(std::move(*s));
    }
    char file[40];
    std::snprintf(file, sizeof file, "frame_%06zu", k);
    std::string csv = "time,id,realizations,x,y,z";
    for (const auto& s : stats) csv += "," + s.name;
    csv += '\n';
    for (std::size_t i = 0; i < n; ++i) {
      append_number(csv, f.time);
      csv += ',';
      append_integer(csv, f.particles.ids[i]);
      csv += ',';
      append_integer(csv, runs.size());
      for (std::size_t a = 0; a < 3; ++a) {
        csv += ',';
        append_number(csv, f.particles.positions[3 * i + a]);
      }
      for (const auto& s : stats) {
        csv += ',';
        append_number(csv, s.values[i]);
      }
      csv += '\n';
    }
    write_file_atomic(out / (std::string(file) + ".csv"), csv);
    write_vtu(out / (std::string(file) + ".vtu"), f.time, f.particles, stats);
    pvd.add(f.time, out / (std::string(file) + ".vtu"));
  }
  return result;
}

}  // namespace sadr::orchestrator
