// SPDX-License-Identifier: MIT
// Scene sections "time" and "output": coupling step, end time, splitting,
// output schedule and formats.
#include <algorithm>
#include <array>
#include <cmath>

#include "scene_parts.hpp"

namespace sadr::orchestrator::detail {

namespace {
constexpr std::array<std::string_view, 4> kTimeKeys{"coupling_step", "end", "splitting",
                                                    "tolerance"};
constexpr std::array<std::string_view, 2> kSplittings{"lie", "strang"};
constexpr std::array<std::string_view, 9> kOutputKeys{
    "directory",        "every",        "times",      "include_initial", "formats", "species",
    "checkpoint_every", "vtk_encoding", "observables"};
constexpr std::array<std::string_view, 4> kObservableKeys{"name", "species", "region", "stat"};
constexpr std::array<std::string_view, 2> kStats{"total", "mean"};
constexpr std::array<std::string_view, 2> kVtkEncodings{"binary", "ascii"};
constexpr std::array<std::string_view, 3> kFormats{"vtu", "vtp", "csv"};

/// Sorted output times in [0, end] with near-duplicates (closer than
/// 1e-9 of the end time or of the period) merged into the later one, and
/// the end time itself always last (the final state is always written).
std::vector<double> normalise_times(std::vector<double> times, double end, double scale) {
  times.push_back(end);
  std::sort(times.begin(), times.end());
  std::vector<double> out;
  const double snap = 1e-9 * std::max(scale, 1e-300);
  for (const double t : times) {
    if (!out.empty() && t - out.back() <= snap)
      out.back() = std::max(t, out.back());
    else
      out.push_back(t);
  }
  out.back() = end;
  return out;
}
/// output.observables: [{name, species, region (default all), stat: total|mean}].
void read_observables(SceneContext& ctx, const Field& out) {
  YamlReader& r = ctx.reader;
  Scene& s = ctx.scene;
  const Field list = YamlReader::child(out, "observables");
  if (!YamlReader::present(list) || !r.expect_sequence(list)) return;
  for (std::size_t k = 0; k < list.node.size(); ++k) {
    const Field f = YamlReader::element(list, k);
    if (!r.expect_map(f, kObservableKeys)) continue;
    ObservableSpec o;
    const auto name = r.string(f, "name", true);
    const auto species = r.string(f, "species", true);
    if (!name || !species) continue;
    o.name = *name;
    o.species = *species;
    const bool clash = s.find_species(o.name) != nullptr ||
                       std::any_of(s.output.observables.begin(), s.output.observables.end(),
                                   [&](const ObservableSpec& x) { return x.name == o.name; });
    if (!valid_identifier(o.name) || clash) {
      r.error(YamlReader::child(f, "name"),
              "'" + o.name +
                  "' cannot name an observable; allowed: [A-Za-z_][A-Za-z0-9_]*, not a species "
                  "and not another observable (they share the species column of "
                  "observables.csv)");
      continue;
    }
    if (std::find(s.output.species.begin(), s.output.species.end(), o.species) ==
        s.output.species.end()) {
      r.error(YamlReader::child(f, "species"),
              "species '" + o.species + "' is not written to the frames; allowed: one of " +
                  "output.species (the observable is computed from the CSV frames)");
      continue;
    }
    o.region = r.string(f, "region", false).value_or(std::string(kAllRegion));
    if (!lookup_region(ctx, YamlReader::child(f, "region"), o.region)) continue;
    o.mean = r.choice(f, "stat", kStats, false, "statistic").value_or("total") == "mean";
    s.output.observables.push_back(std::move(o));
  }
}

}  // namespace

void read_time_and_output(SceneContext& ctx, const Field& root) {
  YamlReader& r = ctx.reader;
  Scene& s = ctx.scene;
  const Field time = YamlReader::child(root, "time");
  bool time_ok = false;
  if (!YamlReader::present(time)) {
    r.error(time, "missing; required: a map with coupling_step and end");
  } else if (r.expect_map(time, kTimeKeys)) {
    const auto tau = r.number(time, "coupling_step", Bound::kPositive, "time", true);
    const auto end = r.number(time, "end", Bound::kNonNegative, "time", true);
    if (auto sp = r.choice(time, "splitting", kSplittings, false, "splitting")) {
      s.time.splitting = *sp == "strang" ? Splitting::kStrang : Splitting::kLie;
    }
    if (tau) s.time.coupling_step = *tau;
    if (end) s.time.end = *end;
    time_ok = tau && end;
    if (tau) read_time_tolerance(ctx, time);
  }

  std::vector<double> times;
  bool include_initial = true;
  double every = 0.0;
  const Field out = YamlReader::child(root, "output");
  if (YamlReader::present(out) && r.expect_map(out, kOutputKeys)) {
    s.output.directory = r.string(out, "directory", false).value_or("");
    include_initial = r.boolean(out, "include_initial", false).value_or(true);
    const Field ev = YamlReader::child(out, "every");
    const Field ts = YamlReader::child(out, "times");
    if (YamlReader::present(ev) && YamlReader::present(ts)) {
      r.error(ts, "give either 'every' or 'times', not both");
    } else if (YamlReader::present(ev)) {
      every = r.number(out, "every", Bound::kPositive, "time", true).value_or(0.0);
      if (every > 0.0 && time_ok) {
        const double n = std::floor(s.time.end / every * (1.0 + 1e-12));
        if (n > 1e7) {
          r.error(ev,
                  format_number(every) + " gives more than 1e7 frames; allowed: a longer period");
        } else {
          for (double k = 1; k <= n; ++k) times.push_back(k * every);
        }
      }
    } else if (r.expect_sequence(ts)) {
      for (std::size_t i = 0; i < ts.node.size(); ++i) {
        const Field e = YamlReader::element(ts, i);
        const auto t = r.number_at(e, Bound::kNonNegative, "time");
        if (!t) continue;
        if (time_ok && *t > s.time.end) {
          r.error(e, format_number(*t) + " is after the end time " + format_number(s.time.end) +
                         "; allowed: 0 <= t <= time.end");
          continue;
        }
        times.push_back(*t);
      }
    }
    s.output.formats.clear();
    if (auto fmts = r.string_list(out, "formats", false)) {
      for (const auto& name : *fmts) {
        if (name == "vtu")
          s.output.formats.push_back(OutputFormat::kVtu);
        else if (name == "vtp")
          s.output.formats.push_back(OutputFormat::kVtp);
        else if (name == "csv")
          s.output.formats.push_back(OutputFormat::kCsv);
        else {
          std::string msg = "unknown output format '" + name + "'";
          if (auto near = nearest_name(name, kFormats)) msg += "; did you mean '" + *near + "'?";
          r.error(YamlReader::child(out, "formats"), msg + " (allowed: vtu, vtp, csv)");
        }
      }
    } else {
      s.output.formats = {OutputFormat::kVtu, OutputFormat::kCsv};
    }
    if (auto names = r.string_list(out, "species", false)) {
      std::vector<std::string_view> known;
      for (const auto& sp : s.species) known.push_back(sp.name);
      for (const auto& a : s.assigned) known.push_back(a.name);
      for (const auto& name : *names) {
        if (s.find_species(name) || s.find_assigned(name)) {
          s.output.species.push_back(name);
          continue;
        }
        std::string msg = "unknown species '" + name + "'";
        if (auto near = nearest_name(name, known)) msg += "; did you mean '" + *near + "'?";
        r.error(YamlReader::child(out, "species"), msg);
      }
    } else {
      for (const auto& sp : s.species) s.output.species.push_back(sp.name);
      for (const auto& a : s.assigned) s.output.species.push_back(a.name);
    }
    s.output.checkpoint_every =
        r.number_or(out, "checkpoint_every", 0.0, Bound::kNonNegative, "time");
    if (auto enc = r.choice(out, "vtk_encoding", kVtkEncodings, false, "VTK encoding")) {
      s.output.vtk_encoding = *enc == "ascii" ? VtkEncoding::kAscii : VtkEncoding::kBinary;
    }
    read_observables(ctx, out);
  } else {
    for (const auto& sp : s.species) s.output.species.push_back(sp.name);
    for (const auto& a : s.assigned) s.output.species.push_back(a.name);
  }
  if (!time_ok) return;
  if (include_initial) times.push_back(0.0);
  const double scale = every > 0.0 ? std::min(every, s.time.coupling_step) : s.time.coupling_step;
  s.output.times = normalise_times(std::move(times), s.time.end, scale);
}

}  // namespace sadr::orchestrator::detail
