// SPDX-License-Identifier: MIT
// `sadr graph SCENE`: the diffusion graph ssa_service builds for a scene's
// initial particles, edge by edge with its weight D_ij and the jump rate
// kappa_s D_ij of every stochastic species; and the graph diagnostics the plan
// prints (sadr/ssa/graph_diagnostics.hpp). The graph is made the way a run
// makes it: Scene -> the SSA Init message -> the service's model conversion
// -> DiffusionGraph::build, so the dump is exactly what the SSA uses.
#include <cstdio>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli.hpp"
#include "commands.hpp"
#include "graph_report.hpp"
#include "sadr/orchestrator/frame_writers.hpp"
#include "sadr/orchestrator/scene_loader.hpp"
#include "sadr/orchestrator/scene_messages.hpp"
#include "sadr/orchestrator/scene_override.hpp"
#include "sadr/orchestrator/seeds.hpp"
#include "sadr/ssa/graph_diagnostics.hpp"
#include "sadr/ssa/ssa_service.hpp"
#include "sadr/wire/convert.hpp"

namespace sadr::orchestrator {
namespace {

struct GraphCommandOptions {
  std::string scene;
  std::vector<std::string> overrides;  ///< --set PATH=VALUE
  std::string format = "json";         ///< json or csv
  std::string output;                  ///< -o FILE ("" = stdout)
};

/// Above this many particles the plan does not build the graph (it would cost
/// the run's own graph build again); `sadr graph` always does.
constexpr std::size_t kPlanGraphLimit = 2'000'000;

struct SsaGraph {
  ssa::Model model;
  std::vector<std::string> species;
  ssa::DiffusionGraph graph;
};

SsaGraph build_ssa_graph(const Scene& scene, const Plan& plan) {
  const auto init = make_ssa_init(scene, plan, realization_seed(scene.seed, 0), scene.particles);
  SsaGraph g;
  const ParticleState particles = wire::from_proto(init.particles(), "init.particles");
  g.model = ssa::model_from_proto(init.model(), particles.size(), g.species);
  g.graph = ssa::DiffusionGraph::build(g.model, particles);
  return g;
}

std::string edges_csv(const SsaGraph& g) {
  std::string out = "source,target,source_kind,target_kind,weight";
  for (const auto& s : g.model.species) out += ",rate_" + s.def.name;
  out += "\n";
  const auto& gr = g.graph;
  for (std::size_t i = 0; i < gr.size(); ++i) {
    for (std::uint32_t k = gr.row_start[i]; k < gr.row_start[i + 1]; ++k) {
      const auto& e = gr.edges[k];
      append_integer(out, i);
      out += ',';
      append_integer(out, e.target);
      out += ',';
      out += to_string(gr.kind[i]);
      out += ',';
      out += to_string(gr.kind[e.target]);
      out += ',';
      append_number(out, e.weight);
      for (const auto& s : g.model.species) {
        out += ',';
        append_number(out, s.def.diffusivity * e.weight);
      }
      out += '\n';
    }
  }
  return out;
}

}  // namespace

GraphReport graph_report(const Scene& scene, const Plan& plan) {
  GraphReport r;
  if (!plan.ssa_service) return r;
  if (scene.particles.size() > kPlanGraphLimit) {
    r.lines.push_back("SSA graph: not diagnosed here (" + std::to_string(scene.particles.size()) +
                      " particles); `sadr graph` does it");
    return r;
  }
  const SsaGraph g = build_ssa_graph(scene, plan);
  const auto d = ssa::diagnose_graph(g.graph, g.model);
  r.lines = d.lines();
  r.warning = d.isolated_warning();
  return r;
}

namespace {

int cmd_graph(const GraphCommandOptions& o) {
  const Scene scene = load_scene(o.scene, parse_overrides(o.overrides));
  const Plan plan = make_plan(scene);
  if (!plan.ssa_service) {
    throw InvalidArgument(o.scene +
                          ": the scene has no stochastic species, so there is no SSA "
                          "graph (ssa_service is not launched)");
  }
  const SsaGraph g = build_ssa_graph(scene, plan);
  const auto d = ssa::diagnose_graph(g.graph, g.model);
  std::string text;
  if (o.format == "csv") {
    text = edges_csv(g);
  } else {
    nlohmann::json j;
    j["scene"] = o.scene;
    j["dimension"] = g.graph.dimension;
    j["smoothing_length"] = g.model.smoothing_length;
    j["regularization"] = g.model.regularization;
    j["convention"] = std::string(ssa::to_string(g.model.convention));
    nlohmann::json species = nlohmann::json::array();
    for (const auto& s : g.model.species) {
      species.push_back({{"name", s.def.name}, {"diffusivity", s.def.diffusivity}});
    }
    j["species"] = species;
    j["voxels"] = {{"volume", g.graph.volume}, {"wall", g.graph.is_wall}};
    nlohmann::json edges = nlohmann::json::array();
    for (std::size_t i = 0; i < g.graph.size(); ++i) {
      for (std::uint32_t k = g.graph.row_start[i]; k < g.graph.row_start[i + 1]; ++k) {
        const double w = g.graph.edges[k].weight;  // packed edge: copy, no reference
        const std::uint32_t target = g.graph.edges[k].target;
        edges.push_back({i, target, w});
      }
    }
    j["edges"] = edges;  // [source, target, D_ij]; the rate of species s is kappa_s D_ij
    j["diagnostics"] = {{"edges", d.edges},
                        {"components", d.components},
                        {"largest_component", d.largest_component},
                        {"isolated", d.isolated},
                        {"min_degree", d.min_degree},
                        {"mean_degree", d.mean_degree},
                        {"max_degree", d.max_degree},
                        {"min_weight", d.min_weight},
                        {"max_weight", d.max_weight},
                        {"min_rate", d.min_rate},
                        {"max_rate", d.max_rate}};
    if (d.isolated_example) j["diagnostics"]["isolated_example"] = *d.isolated_example;
    text = j.dump(1) + "\n";
  }
  if (o.output.empty()) {
    std::fputs(text.c_str(), stdout);
  } else {
    std::ofstream f(o.output, std::ios::binary | std::ios::trunc);
    f << text;
    if (!f.flush()) throw IoError("cannot write '" + o.output + "'");
  }
  for (const auto& line : d.lines()) std::fprintf(stderr, "sadr: %s\n", line.c_str());
  if (!d.isolated_warning().empty()) {
    std::fprintf(stderr, "%s: warning: %s\n", o.scene.c_str(), d.isolated_warning().c_str());
  }
  return kExitOk;
}

}  // namespace

Subcommand add_graph_command(CLI::App& app) {
  auto o = std::make_shared<GraphCommandOptions>();
  auto* graph = app.add_subcommand(
      "graph",
      "dump the SSA diffusion graph of a scene (edges, D_ij, jump rates) and its "
      "diagnostics (docs/cli.md)");
  graph->add_option("scene", o->scene, "scene file (YAML)")->required()->check(CLI::ExistingFile);
  graph->add_option("--format", o->format, "json (default) or csv")
      ->check(CLI::IsMember({"json", "csv"}));
  graph->add_option("-o,--output", o->output, "write to FILE instead of stdout");
  add_set_option(graph, o->overrides);
  return {graph, [o] { return cmd_graph(*o); }};
}

}  // namespace sadr::orchestrator
