// SPDX-License-Identifier: MIT
/// \file service_interfaces.hpp
/// What the coupling loop asks of the two services, in domain terms: advance,
/// geometry, copy numbers, concentrations, snapshot, restore. FluidClient and
/// SsaClient (service_clients.hpp) implement these over the wire; the loop's
/// unit tests implement them in-process (tests/orchestrator). No protobuf here.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "sadr/common/particle_state.hpp"

namespace sadr::common::v1 {
class ParticleState;  // generated (particles.proto); only service_clients.cpp looks inside
}

namespace sadr::orchestrator {

/// Copy numbers X_is of stochastic species: names[k] has values[k], one per particle.
struct SpeciesCounts {
  std::vector<std::string> names;
  std::vector<std::vector<std::int64_t>> values;
  [[nodiscard]] bool empty() const { return names.empty(); }
};

/// Concentrations by species: name, one value per particle.
using SpeciesConcentrations = std::vector<std::pair<std::string, std::vector<double>>>;

/// The geometry one fluid stage hands to the next SSA stage (positions,
/// densities, masses, kinds), wherever it travels: a generation number of the
/// run's shared-memory segment, or the arrays inline. Opaque to the loop.
class Geometry {
 public:
  Geometry() = default;
  /// Generation `generation` (> 0) of the run's shared-memory segment.
  static Geometry shared_memory(std::uint64_t generation) {
    Geometry g;
    g.generation_ = generation;
    return g;
  }
  /// The arrays themselves (inline in the messages).
  static Geometry inline_arrays(std::shared_ptr<common::v1::ParticleState> state) {
    Geometry g;
    g.inline_ = std::move(state);
    return g;
  }
  [[nodiscard]] bool empty() const { return generation_ == 0 && !inline_; }
  [[nodiscard]] std::uint64_t generation() const { return generation_; }  ///< 0: not shared
  [[nodiscard]] const std::shared_ptr<common::v1::ParticleState>& arrays() const { return inline_; }

 private:
  std::uint64_t generation_ = 0;
  std::shared_ptr<common::v1::ParticleState> inline_;
};

/// The force and torque the fluid exerted on one body (scene fluid.body_forces), averaged over
/// a fluid stage.
struct BodyForceSample {
  std::string name;
  std::array<double, 3> force{}, torque{}, reference{};
};

/// What one fluid stage reports.
struct FluidStep {
  double time = 0.0;  ///< simulated time after the stage [time]
  std::uint32_t substeps = 0;
  bool particles_moved = false;
  double compute_seconds = 0.0;  ///< inside the backend [s]
  /// The smallest binding stability limit the stage's sub-steps met [time] (+inf: none binds or
  /// not reported) and its name ("reaction", ...).
  double stable_time_step = std::numeric_limits<double>::infinity();
  std::string limiting_criterion;
  Geometry geometry;  ///< when asked for (advance's want_geometry)
  /// advance's return_concentrations after the stage (hybrid reactions), in that order.
  SpeciesConcentrations concentrations;
  /// fluid.body_forces in scene order (empty: none asked).
  std::vector<BodyForceSample> body_forces;
};

/// The fluid state of a frame.
struct FluidFrame {
  ParticleState particles;  ///< with velocities
  /// Deterministic species asked for, in that order: name, one value per particle.
  SpeciesConcentrations concentrations;
};

class FluidService {
 public:
  virtual ~FluidService() = default;
  /// One fluid stage of length dt (coupling step `step_index`'s call). When
  /// `counts` is not empty, its species' concentrations are first set to
  /// X_is / V_i with the fluid's own volumes (the back-transfer). With
  /// `want_geometry` the geometry after the stage comes back for the SSA, and the
  /// concentrations of `return_concentrations` (hybrid reactions' frozen species).
  virtual FluidStep advance(std::uint64_t step_index, double dt, bool want_geometry,
                            const SpeciesCounts& counts,
                            const std::vector<std::string>& return_concentrations) = 0;
  /// The geometry of the current state (when an advance returned none).
  virtual Geometry geometry() = 0;
  /// Particles with velocities and the named deterministic concentrations.
  virtual FluidFrame frame(const std::vector<std::string>& species) = 0;
  /// The complete service state as bytes (deterministic: equal states, equal bytes).
  virtual std::string snapshot(std::uint64_t step_index) = 0;
  virtual void restore(const std::string& snapshot) = 0;
};

/// What one SSA stage reports.
struct SsaStep {
  double time = 0.0;  ///< == t_end [time]
  std::uint64_t events = 0;
  /// Molecules moved by leaps (ssa.method adaptive; 0 for the exact method): each moves one
  /// molecule between two voxels, as a diffusion event does.
  std::uint64_t leaped_molecules = 0;
  double graph_seconds = 0.0;  ///< graph, rates and queue rebuild [s]
  double nsm_seconds = 0.0;    ///< event loop [s]
  SpeciesCounts counts;        ///< advance's return_counts, after the stage
};

class SsaService {
 public:
  virtual ~SsaService() = default;
  /// Runs the NSM to the absolute time t_end, first rebuilding the graph from
  /// `geometry` unless it is empty (particles did not move); returns the copy
  /// numbers of `return_counts` after the stage. `frozen`: the deterministic
  /// concentrations the hybrid reactions' laws hold over the stage (empty: none).
  virtual SsaStep advance(std::uint64_t step_index, double t_end, Geometry geometry,
                          const std::vector<std::string>& return_counts,
                          const SpeciesConcentrations& frozen) = 0;
  /// Copy numbers of the named species (empty: all).
  virtual SpeciesCounts counts(const std::vector<std::string>& species) = 0;
  virtual std::string snapshot(std::uint64_t step_index) = 0;
  virtual void restore(const std::string& snapshot) = 0;
};

}  // namespace sadr::orchestrator
