// SPDX-License-Identifier: MIT
// Flow replay in a sweep (sweep_flows.hpp).
#include "sweep_flows.hpp"

#include <map>

#include "sadr/orchestrator/scene_loader.hpp"
#include "sadr/orchestrator/scene_messages.hpp"

namespace sadr::orchestrator {

void decide_sweep_flows(SweepManifest& m, bool refused) {
  std::vector<PointFlow> flows(m.points.size());
  std::map<std::string, std::vector<std::size_t>> points_of;  // fluid key -> points
  for (const auto& p : m.points) {
    const Scene scene =
        load_scene(m.base_scene, m.overrides_of(m.runs.at(p.index * m.realizations)));
    const Plan plan = make_plan(scene);
    PointFlow& f = flows[p.index];
    f.reason = plan.flow_replay_reason;
    if (!plan.flow_replay_allowed) continue;
    try {
      f.fluid_key = fluid_key(scene, plan);
    } catch (const Error& e) {  // a scene the services refuse: its runs say why
      f.reason = std::string("no fluid key: ") + e.what();
      continue;
    }
    points_of[f.fluid_key].push_back(p.index);
  }
  for (auto& f : flows) {
    if (f.fluid_key.empty()) continue;
    const auto& points = points_of.at(f.fluid_key);
    const std::size_t runs = points.size() * m.realizations;
    if (refused) {
      f.reason = "--no-flow-replay";
    } else if (runs < 2) {
      f.reason = "no other run of the sweep has this fluid";
    } else {
      f.replay = true;
      std::string list;
      for (const std::size_t p : points) list += (list.empty() ? "" : " ") + std::to_string(p);
      f.reason = "the fluid is the same in " + std::to_string(runs) + " runs (point" +
                 (points.size() > 1 ? "s " : " ") + list + "): computed once into " +
                 flow_tape_file(f.fluid_key) + ", replayed to each";
    }
  }
  m.flows = std::move(flows);
}

std::string flow_line(const PointFlow& flow) {
  return std::string("flow replay: ") + (flow.replay ? "on" : "off") + " (" + flow.reason + ")";
}

void decide_sweep_task_flow(Plan& plan, const SweepManifest& m, const SweepRun& run,
                            const std::filesystem::path& run_dir, bool resumed) {
  plan.flow_replay = false;
  if (!plan.flow_replay_allowed) return;  // make_plan's reason stays
  const PointFlow* f = run.point < m.flows.size() ? &m.flows[run.point] : nullptr;
  if (resumed && checkpoint_replays_flow(run_dir)) {
    plan.flow_replay = true;
    plan.flow_replay_reason = "resumed: its checkpoint is a place in the flow replay file";
  } else if (resumed && f && f->replay) {
    plan.flow_replay_reason = "resumed: its checkpoint holds the state of its own fluid";
  } else if (f) {
    plan.flow_replay = f->replay;
    plan.flow_replay_reason = f->reason;
  } else {
    plan.flow_replay_reason = "not decided by the sweep (sweep.json has no flow_replay)";
  }
}

std::size_t remove_finished_flows(const SweepManifest& m, const std::filesystem::path& dir) {
  if (m.flows.size() != m.points.size()) return 0;
  std::map<std::string, bool> finished;  // fluid key -> every run that replays it is ok
  for (const auto& r : m.runs) {
    const PointFlow& f = m.flows[r.point];
    if (!f.replay) continue;
    auto [it, added] = finished.emplace(f.fluid_key, true);
    it->second = it->second && r.state == RunState::kOk;
  }
  std::size_t removed = 0;
  for (const auto& [key, done] : finished) {
    if (!done) continue;
    std::filesystem::path tape = dir / flow_tape_file(key);
    removed += std::filesystem::remove(tape) ? 1 : 0;
    std::filesystem::remove(tape.replace_extension(".lock"));
  }
  std::error_code ec;
  std::filesystem::remove(dir / "flows", ec);  // only when empty
  return removed;
}

}  // namespace sadr::orchestrator
