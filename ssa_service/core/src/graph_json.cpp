// SPDX-License-Identifier: MIT
#include "sadr/ssa/graph_json.hpp"

#include <cmath>
#include <cstdio>
#include <string>

namespace sadr::ssa {

namespace {
std::string num(double v) {
  if (std::isinf(v)) return "\"inf\"";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}
template <typename T, typename F>
std::string list(const std::vector<T>& v, F f) {
  std::string s = "[";
  for (std::size_t k = 0; k < v.size(); ++k) s += (k ? ", " : "") + f(v[k]);
  return s + "]";
}
}  // namespace

std::string graph_to_json(const DiffusionGraph& graph, const LinearRdmeSpec& spec) {
  std::string s = "{\n \"n_voxels\": " + std::to_string(graph.size()) + ",\n \"edges\": [";
  bool first = true;
  for (std::size_t i = 0; i < graph.size(); ++i) {
    const std::uint32_t end =
        spec.include_wall_edges && !graph.is_wall[i] ? graph.row_start[i + 1] : graph.split[i];
    if (!spec.include_wall_edges && graph.is_wall[i]) continue;
    for (std::uint32_t k = graph.row_start[i]; k < end; ++k) {
      s += first ? "\n  [" : ",\n  [";
      first = false;
      s += std::to_string(i) + ", " + std::to_string(graph.edges[k].target) + ", " +
           num(spec.kappa * graph.edges[k].weight) + "]";
    }
  }
  s += "\n ],\n";
  s += " \"k\": " + num(spec.decay) + ",\n";
  s += " \"b\": " +
       (spec.birth.size() == 1 ? num(spec.birth[0])
                               : list(spec.birth, [](double v) { return num(v); })) +
       ",\n";
  s += " \"x0\": " + list(spec.x0, [](std::int64_t v) { return std::to_string(v); }) + ",\n";
  s += " \"fixed\": {\"index\": " +
       list(spec.fixed_index, [](std::uint32_t v) { return std::to_string(v); }) +
       ", \"count\": " + list(spec.fixed_count, [](std::int64_t v) { return std::to_string(v); }) +
       "},\n";
  s += " \"times\": " + list(spec.times, [](double v) { return num(v); }) + ",\n";
  s += std::string(" \"variance\": ") + (spec.variance ? "true" : "false") + "\n}\n";
  return s;
}

}  // namespace sadr::ssa
