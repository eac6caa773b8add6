// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/sweep_spec.hpp"

#include <array>

#include "sadr/common/input_file.hpp"
#include "sadr/common/status.hpp"
#include "sadr/orchestrator/hash.hpp"
#include "yaml_reader.hpp"

namespace sadr::orchestrator {
namespace {
using detail::Field;
using detail::YamlReader;

/// A YAML value as one line of YAML text (the VALUE of an override).
std::string value_text(const YAML::Node& node) {
  if (node.IsScalar()) return node.Scalar();
  YAML::Emitter e;
  e << YAML::Flow << node;
  return e.c_str();
}

/// The columns of a `grid` or `zip` map: path -> list of values.
std::vector<std::pair<std::string, std::vector<std::string>>> columns(YamlReader& r,
                                                                      const Field& f) {
  std::vector<std::pair<std::string, std::vector<std::string>>> out;
  if (!f.node.IsMap()) {
    r.error(f, "expected a map PATH: [values...]");
    return out;
  }
  for (const auto& kv : f.node) {
    const std::string path = kv.first.Scalar();
    const Field col = YamlReader::child(f, path);
    try {
      parse_override(path + "=x");
    } catch (const Error& e) {
      r.error(col, e.what());
      continue;
    }
    if (!kv.second.IsSequence() || kv.second.size() == 0) {
      r.error(col, "expected a non-empty list of values");
      continue;
    }
    std::vector<std::string> values;
    for (const auto& v : kv.second) values.push_back(value_text(v));
    out.emplace_back(path, std::move(values));
  }
  return out;
}

void read_parameters(YamlReader& r, const Field& root, SweepSpec& s) {
  const Field p = YamlReader::child(root, "parameters");
  if (!YamlReader::present(p)) {  // one point: the base scene itself
    s.points.push_back({0, {}});
    return;
  }
  static constexpr std::array<std::string_view, 3> kKeys{"grid", "zip", "points"};
  if (!r.expect_map(p, kKeys)) return;
  const Field points = YamlReader::child(p, "points");
  if (YamlReader::present(points)) {
    if (YamlReader::present(YamlReader::child(p, "grid")) ||
        YamlReader::present(YamlReader::child(p, "zip"))) {
      r.error(points, "explicit points cannot be combined with grid or zip");
      return;
    }
    if (!r.expect_sequence(points)) return;
    for (std::size_t i = 0; i < points.node.size(); ++i) {
      const Field pt = YamlReader::element(points, i);
      if (!pt.node.IsMap()) {
        r.error(pt, "expected a map PATH: value");
        continue;
      }
      SweepPoint sp{i, {}};
      std::vector<std::string> paths;
      for (const auto& kv : pt.node) {
        paths.push_back(kv.first.Scalar());
        sp.overrides.push_back({kv.first.Scalar(), value_text(kv.second)});
      }
      if (i == 0) s.parameters = paths;
      if (paths != s.parameters) {
        r.error(pt, "every point must set the same paths in the same order as point 0");
      }
      s.points.push_back(std::move(sp));
    }
    return;
  }
  // grid (cartesian product, the last path varying fastest) x zip (rows).
  const auto grid = YamlReader::present(YamlReader::child(p, "grid"))
                        ? columns(r, YamlReader::child(p, "grid"))
                        : decltype(columns(r, p)){};
  const Field zf = YamlReader::child(p, "zip");
  const auto zip = YamlReader::present(zf) ? columns(r, zf) : decltype(columns(r, p)){};
  std::size_t rows = zip.empty() ? 1 : zip[0].second.size();
  for (const auto& [path, values] : zip) {
    if (values.size() != rows) {
      r.error(YamlReader::child(zf, path), "has " + std::to_string(values.size()) +
                                               " values but '" + zip[0].first + "' has " +
                                               std::to_string(rows) +
                                               "; zipped lists must have "
                                               "equal lengths");
    }
  }
  for (const auto& c : grid) s.parameters.push_back(c.first);
  for (const auto& c : zip) s.parameters.push_back(c.first);
  std::size_t total = rows;
  for (const auto& c : grid) total *= c.second.size();
  if (total > 1000000) {
    r.error(p, std::to_string(total) + " points; at most 1000000 are allowed");
    return;
  }
  for (std::size_t k = 0; k < total; ++k) {
    SweepPoint sp{k, {}};
    std::size_t rest = k / rows;
    std::vector<SceneOverride> g(grid.size());
    for (std::size_t c = grid.size(); c-- > 0;) {
      const auto& values = grid[c].second;
      g[c] = {grid[c].first, values[rest % values.size()]};
      rest /= values.size();
    }
    sp.overrides = g;
    for (const auto& [path, values] : zip) {
      sp.overrides.push_back({path, k % rows < values.size() ? values[k % rows] : ""});
    }
    s.points.push_back(std::move(sp));
  }
}

void read_executor(YamlReader& r, const Field& root, ExecutorSpec& e) {
  const Field f = YamlReader::child(root, "executor");
  if (!YamlReader::present(f)) return;
  if (f.node.IsScalar()) {
    static constexpr std::array<std::string_view, 2> kTypes{"local", "slurm"};
    if (auto t = r.choice(root, "executor", kTypes, true, "executor")) e.type = *t;
    return;
  }
  static constexpr std::array<std::string_view, 6> kKeys{
      "type", "workers", "cpus_per_task", "partition", "sbatch_args", "poll_seconds"};
  if (!r.expect_map(f, kKeys)) return;
  static constexpr std::array<std::string_view, 2> kTypes{"local", "slurm"};
  e.type = r.choice(f, "type", kTypes, false, "executor").value_or("local");
  e.workers = static_cast<int>(r.integer(f, "workers", 0, 4096, false).value_or(0));
  e.cpus_per_task = static_cast<int>(r.integer(f, "cpus_per_task", 1, 4096, false).value_or(1));
  e.partition = r.string(f, "partition", false).value_or("");
  e.sbatch_args = r.string_list(f, "sbatch_args", false).value_or(std::vector<std::string>{});
  e.poll_seconds = r.number_or(f, "poll_seconds", 2.0, detail::Bound::kPositive, "s");
}

}  // namespace

SweepSpec parse_sweep_spec(const std::string& text, const std::filesystem::path& source) {
  Diagnostics diag(source.string());
  YAML::Node doc;
  try {
    doc = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    diag.error({e.mark.line + 1, e.mark.column + 1}, "", "YAML syntax error: " + e.msg);
    diag.throw_if_any();
  }
  YamlReader r(diag);
  Field root{doc, "", {1, 1}};
  static constexpr std::array<std::string_view, 8> kKeys{
      "scene", "parameters", "realizations", "seed", "executor", "retries", "keep", "output"};
  if (!r.expect_map(root, kKeys)) diag.throw_if_any();
  SweepSpec s;
  s.source = source;
  if (auto scene = r.string(root, "scene", true)) {
    std::filesystem::path p(*scene);
    s.base_scene = p.is_absolute() ? p : std::filesystem::absolute(source).parent_path() / p;
    if (!std::filesystem::is_regular_file(s.base_scene)) {
      r.error(YamlReader::child(root, "scene"), s.base_scene.string() + " is not a readable file");
    }
  }
  s.realizations = r.integer(root, "realizations", 1, 1000000, false).value_or(1);
  if (auto seed = r.integer(root, "seed", 0, UINT64_MAX, false)) s.seed = *seed;
  s.retries = static_cast<int>(r.integer(root, "retries", 0, 100, false).value_or(1));
  static constexpr std::array<std::string_view, 2> kKeep{"all", "aggregates"};
  s.keep = r.choice(root, "keep", kKeep, false, "keep policy").value_or("aggregates") == "all"
               ? KeepPolicy::kAll
               : KeepPolicy::kAggregates;
  s.output = r.string(root, "output", false).value_or("");
  read_executor(r, root, s.executor);
  read_parameters(r, root, s);
  diag.throw_if_any();
  if (s.points.empty()) throw InvalidArgument(source.string() + ": the sweep has no points");
  return s;
}

SweepSpec load_sweep_spec(const std::filesystem::path& path) {
  return parse_sweep_spec(read_file_bytes(path, kMaxSceneFileBytes, "sweep file"), path);
}

std::string_view to_string(KeepPolicy keep) {
  return keep == KeepPolicy::kAll ? "all" : "aggregates";
}

}  // namespace sadr::orchestrator
