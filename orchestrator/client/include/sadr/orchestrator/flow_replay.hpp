// SPDX-License-Identifier: MIT
/// \file flow_replay.hpp
/// Flow replay (plan.hpp): when the fluid is the same in every realization, an
/// ensemble computes it once, in a fluid-only pass of the coupling loop
/// (record_flow: the loop with an SSA that does nothing), and writes every
/// answer of the fluid to a flow replay file (flow_tape.hpp). Each realization
/// then runs the loop against FlowReplay, a FluidService that answers from the
/// file and checks that every call is the one recorded; frames, the SSA's
/// geometry and checkpoints are those of a run that steps the fluid, byte for byte.
#pragma once

#include <atomic>
#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "sadr/orchestrator/flow_tape.hpp"
#include "sadr/orchestrator/plan.hpp"
#include "sadr/orchestrator/scene.hpp"
#include "sadr/orchestrator/service_interfaces.hpp"

namespace sadr::orchestrator {

/// Writes every call of `inner` with its answer to `tape`. The geometry must
/// come inline (no shared-memory channel). snapshot/restore are refused.
class FlowRecorder final : public FluidService {
 public:
  FlowRecorder(FluidService& inner, FlowTapeWriter& tape) : inner_(inner), tape_(tape) {}
  FluidStep advance(std::uint64_t step_index, double dt, bool want_geometry,
                    const SpeciesCounts& counts,
                    const std::vector<std::string>& return_concentrations) override;
  Geometry geometry() override;
  FluidFrame frame(const std::vector<std::string>& species) override;
  std::string snapshot(std::uint64_t step_index) override;
  void restore(const std::string& snapshot) override;

 private:
  FluidService& inner_;
  FlowTapeWriter& tape_;
};

/// Answers the fluid calls from a flow replay file, in order. A call that is
/// not the next one recorded is an error naming both. Its snapshot is its
/// place in the file (is_flow_replay_snapshot); restore continues there.
class FlowReplay final : public FluidService {
 public:
  /// Opens `path`; its header's fluid key must be `fluid_key` (fluid_key()).
  FlowReplay(const std::filesystem::path& path, const std::string& fluid_key);
  FluidStep advance(std::uint64_t step_index, double dt, bool want_geometry,
                    const SpeciesCounts& counts,
                    const std::vector<std::string>& return_concentrations) override;
  Geometry geometry() override;
  FluidFrame frame(const std::vector<std::string>& species) override;
  std::string snapshot(std::uint64_t step_index) override;
  void restore(const std::string& snapshot) override;

 private:
  FlowRecord expect(FlowCall call, const std::string& asked);
  FlowTapeReader tape_;
};

/// The snapshot bytes are a FlowReplay's (a replayed realization's checkpoint).
bool is_flow_replay_snapshot(const std::string& bytes);

struct RecordFlowOptions {
  std::filesystem::path path;  ///< the flow replay file to write
  std::chrono::milliseconds timeout{std::chrono::seconds(120)};
  std::function<void()> liveness;                ///< see RunOptions::liveness
  const std::atomic<bool>* interrupt = nullptr;  ///< stop (the file is not written)
};

struct RecordedFlow {
  bool complete = false;  ///< false: interrupted, no file
  std::uint64_t records = 0;
  std::uint64_t bytes = 0;
  double seconds = 0.0;  ///< wall time of the pass
};

/// The fluid-only pass: initialises the fluid_service at `fluid_endpoint` as
/// realization 0 would, runs the coupling loop of `plan` with an SSA that does
/// nothing, and records every fluid call (frames included) to options.path.
RecordedFlow record_flow(const Scene& scene, const Plan& plan, const std::string& fluid_endpoint,
                         const RecordFlowOptions& options);

}  // namespace sadr::orchestrator
