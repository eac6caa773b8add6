// SPDX-License-Identifier: MIT
/// \file rdme_state.hpp
/// The state both solvers share: model, diffusion graph, compiled reactions,
/// copy numbers, reservoirs, and the per-voxel rate / event-firing kernels.
/// The solvers (NsmSolver, DirectSolver) add only time and event selection.
///
/// Copy numbers are stored species-major: X_si at counts[s * N + i].
/// Boundary semantics per species s and voxel i:
///  - s has a WallReservoir and i is a wall particle: X_si is held at
///    round(C V_i); it emits into non-wall neighbours, jumps in are absorbed.
///  - s has a reservoir, i is not a wall: jumps go to all neighbours
///    (into a wall = absorbed).
///  - s has no reservoir: walls are no-flux for s: no jumps into or out of
///    wall particles.
///  - a wall particle that is free for s (Model::free_walls) is an ordinary
///    voxel for s (like a fluid particle in all of the above).
/// In general (VoxelRole): an edge i -> j is used by s unless i or j is kClosed
/// for s or both are kReservoir.
#pragma once

#include <cassert>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "sadr/common/particle_state.hpp"
#include "sadr/ssa/diffusion_graph.hpp"
#include "sadr/ssa/event_heap.hpp"
#include "sadr/ssa/graph_builder.hpp"
#include "sadr/ssa/model.hpp"
#include "sadr/ssa/reaction_table.hpp"

namespace sadr::ssa {

inline constexpr std::uint32_t kNoVoxel = std::numeric_limits<std::uint32_t>::max();

class RdmeState {
 public:
  /// Validates the model (throws InvalidArgument).
  explicit RdmeState(Model model);

  [[nodiscard]] const Model& model() const { return model_; }
  [[nodiscard]] bool has_graph() const { return !graph_.row_start.empty(); }
  [[nodiscard]] std::size_t voxel_count() const { return graph_.size(); }
  [[nodiscard]] int species_count() const { return static_cast<int>(model_.species.size()); }
  [[nodiscard]] const DiffusionGraph& graph() const { return graph_; }
  /// The per-step graph builder (candidate list; its counters for tests and benchmarks).
  [[nodiscard]] const GraphBuilder& graph_builder() const { return builder_; }
  [[nodiscard]] const ReactionTable& reactions() const { return table_; }
  /// The particle arrays the current graph was built from.
  [[nodiscard]] const ParticleState& graph_inputs() const { return inputs_; }

  /// Rebuilds graph and reaction constants from `particles` unless positions,
  /// densities, masses and kinds equal the current ones. The first call sets
  /// N and zero counts; later calls must keep N. A rebuild re-imposes reservoir counts
  /// and keeps the cached rates (those of the old graph: the solver rescales its
  /// pending times from them). @return true if the graph was rebuilt.
  bool update_graph(const ParticleState& particles);

  /// Sets X_s for all voxels (then re-imposes reservoirs); validates.
  void set_counts(int species, std::span<const std::int64_t> counts);
  [[nodiscard]] std::span<const std::int64_t> counts(int species) const;
  /// All counts, species-major.
  [[nodiscard]] std::span<const std::int64_t> all_counts() const { return counts_; }
  /// Replaces all counts (species-major, as in a snapshot) without re-imposing anything.
  void restore_counts(std::vector<std::int64_t> counts);
  /// Sets the reservoir counts of wall voxels; returns true if any changed.
  bool apply_reservoirs();
  /// Sets the inputs of the external rate laws (reactions().has_external_laws()):
  /// the time t they see and the frozen species' concentrations (model().frozen_species
  /// major, one per voxel; finite, >= 0), and recomputes those laws' propensities.
  /// Requires a graph. Throws InvalidArgument on a wrong size or value.
  void set_inputs(double t, std::span<const double> frozen);
  [[nodiscard]] double input_time() const { return table_.input_time(); }
  [[nodiscard]] const std::vector<double>& frozen() const { return table_.frozen(); }

  /// Total reaction propensity of voxel i [1/T].
  [[nodiscard]] double reaction_rate(std::uint32_t i) const {
    if (!voxels_[i].active) return 0.0;
    double a = 0;
    for (std::size_t r = 0; r < table_.reaction_count(); ++r) a += reaction_propensity(r, i);
    return a;
  }
  /// Propensity of reaction r in voxel i [1/T]: mass action from the counts, a rate
  /// law from its cache (kept current by refresh_laws: the SSA's dependency graph).
  [[nodiscard]] double reaction_propensity(std::size_t r, std::uint32_t i) const {
    const int k = table_.reaction(r).law;
    return k < 0 ? table_.propensity(r, i, counts_.data(), n_)
                 : law_a_[i * table_.law_count() + static_cast<std::size_t>(k)];
  }
  /// What voxel i is for species s (boundary semantics above).
  enum class VoxelRole : std::uint8_t {
    kOpen,       ///< fluid particle or free wall: ordinary voxel
    kReservoir,  ///< wall reservoir of s: count held fixed
    kClosed,     ///< no-flux wall for s: no jumps in or out
  };
  [[nodiscard]] VoxelRole role(int s, std::uint32_t i) const {
    if (!graph_.is_wall[i]) return VoxelRole::kOpen;
    if (free_slot_[s] >= 0 && free_mask_[static_cast<std::size_t>(free_slot_[s]) * n_ + i]) {
      return VoxelRole::kOpen;
    }
    return reservoir_[s] ? VoxelRole::kReservoir : VoxelRole::kClosed;
  }
  /// Whether species s jumps along out-edge k of voxel i (k in i's row).
  [[nodiscard]] bool uses_edge(int s, std::uint32_t i, std::uint32_t k) const {
    const VoxelRole a = role(s, i);
    if (a == VoxelRole::kClosed) return false;
    const VoxelRole b = role(s, graph_.edges[k].target);
    return b != VoxelRole::kClosed && !(a == VoxelRole::kReservoir && b == VoxelRole::kReservoir);
  }
  /// Out-weight sum [1/L^2] that species s uses in voxel i (boundary semantics above).
  [[nodiscard]] double jump_weight_sum(int s, std::uint32_t i) const {
    const VoxelRecord& v = voxels_[i];
    if (!has_walls_) return v.sum_all;
    if (free_slot_[s] >= 0) return free_sum_[static_cast<std::size_t>(free_slot_[s]) * n_ + i];
    if (v.is_wall) return reservoir_[s] ? graph_.sum_nowall[i] : 0.0;
    return reservoir_[s] ? v.sum_all : graph_.sum_nowall[i];
  }
  /// Total diffusion propensity of voxel i [1/T].
  [[nodiscard]] double diffusion_rate(std::uint32_t i) const {
    double a = 0;
    for (int s : diffusing_) {
      a += kappa_[s] * static_cast<double>(counts_[s * n_ + i]) * jump_weight_sum(s, i);
    }
    return a;
  }
  [[nodiscard]] double total_rate(std::uint32_t i) const {
    return reaction_rate(i) + diffusion_rate(i);
  }

  /// Fires the event of voxel i selected by u in [0, total_rate(i)) (one
  /// uniform draw scaled by the total): reactions first, then diffusion by
  /// species and neighbour, by linear search over the cumulative propensities.
  /// @return the other voxel whose counts changed (a jump target), or kNoVoxel.
  std::uint32_t fire(std::uint32_t i, double u);

  // ---- the adaptive SSA's exact part (rdme_masked.cpp; the exact NSM never calls these) ----
  // `leaped` has one byte per (species, voxel), species-major: a non-zero byte removes the
  // diffusion of that pair from the exact channels (adaptive_leap.hpp leaps it instead).
  /// total_rate(i) without the leaped pairs' diffusion; the same bits when none is leaped.
  [[nodiscard]] double total_rate_masked(std::uint32_t i, const std::uint8_t* leaped) const;
  /// fire() over the channels total_rate_masked() sums (same order and round-off fallback).
  std::uint32_t fire_masked(std::uint32_t i, double u, const std::uint8_t* leaped);
  /// X_si += delta (a leap's move; the caller keeps X_si >= 0 and never moves a held
  /// reservoir count) and refreshes the rate laws that read it.
  void add_count(int s, std::uint32_t i, std::int64_t delta) {
    counts_[static_cast<std::size_t>(s) * n_ + i] += delta;
    assert(counts_[static_cast<std::size_t>(s) * n_ + i] >= 0);
    refresh_laws(s, i);
  }
  /// Diffusivity kappa_s [L^2/T].
  [[nodiscard]] double kappa(int s) const { return kappa_[s]; }

  /// Species with kappa > 0 (the only ones with diffusion bookkeeping).
  [[nodiscard]] const std::vector<int>& diffusing_species() const { return diffusing_; }
  /// Whether species s is held fixed in voxel i (reservoir wall).
  [[nodiscard]] bool fixed(int s, std::uint32_t i) const {
    return reservoir_[s] && role(s, i) == VoxelRole::kReservoir;
  }
  /// Reservoir count of species s in wall voxel i (requires fixed(s, i)).
  [[nodiscard]] std::int64_t reservoir_count(int s, std::uint32_t i) const;
  /// Applies reaction r in voxel i (counts never go negative).
  void apply_reaction(std::size_t r, std::uint32_t i);
  /// Moves one molecule of s from i to j; returns j if X_sj changed, else kNoVoxel.
  std::uint32_t apply_jump(int s, std::uint32_t i, std::uint32_t j);
  /// End of the edge range species s scans in row i; within it, edges with
  /// !uses_edge() are skipped only for species with free walls (has_free_walls()).
  [[nodiscard]] std::uint32_t edge_end(int s, std::uint32_t i) const {
    const VoxelRecord& v = voxels_[i];
    if (!has_walls_ || free_slot_[s] >= 0) return v.end;
    if (v.is_wall || !reservoir_[s]) return v.split;
    return v.end;
  }
  /// Whether some wall particle is free for species s.
  [[nodiscard]] bool has_free_walls(int s) const { return has_walls_ && free_slot_[s] >= 0; }

  /// Hints the memory system that voxel i fires next: prefetches its out-edges
  /// (reading its record: the event loop calls this for the new tree top, whose
  /// record and counts prefetch_record() requested one event earlier, while it
  /// still updates the previous event's jump target).
  void prefetch(std::uint32_t i) const {
    const VoxelRecord& v = voxels_[i];  // a demand load of the record
    if (v.begin < v.end) {
      const DiffusionGraph::Edge* edges = graph_.edges.data();
      detail::prefetch_line(edges + v.begin);      // first and last line
      detail::prefetch_line(edges + (v.end - 1));  // of the edge row
    }
  }

  /// Prefetches voxel i's record and counts (no load needed: the event loop calls
  /// this two events ahead; prefetch() follows one event ahead, when the record is
  /// in cache and gives the edge row's address).
  void prefetch_record(std::uint32_t i) const {
    detail::prefetch_line(voxels_.data() + i);
    for (int s : diffusing_) detail::prefetch_line(counts_.data() + s * n_ + i);
  }

  /// Hints that voxel i's record and reaction constants are read soon (the jump
  /// target's rate update; its counts line was just written by fire()).
  void prefetch_target(std::uint32_t i) const {
    detail::prefetch_line(voxels_.data() + i);
    table_.prefetch(i);
  }

  /// Solver scratch: the cached total rate a_i of voxel i [1/T] (NsmSolver keeps it
  /// here, in the same cache line as the voxel's graph data).
  [[nodiscard]] double& cached_rate(std::uint32_t i) { return voxels_[i].rate; }
  [[nodiscard]] double cached_rate(std::uint32_t i) const { return voxels_[i].rate; }

 private:
  /// Everything the event loop reads about a voxel, in one 32-byte record
  /// (one cache line holds two voxels): measured 3x faster than separate
  /// arrays on the 32^3 lattice benchmark (docs/ssa-core.md).
  struct alignas(32) VoxelRecord {
    double rate = 0;          ///< solver scratch (cached a_i) [1/T]
    double sum_all = 0;       ///< sum_j D_ij [1/L^2]
    std::uint32_t begin = 0;  ///< first out-edge
    std::uint32_t split = 0;  ///< first out-edge to a wall particle
    std::uint32_t end = 0;    ///< one past the last out-edge
    std::uint8_t is_wall = 0;
    std::uint8_t active = 0;  ///< some reaction can fire here
  };
  static_assert(sizeof(VoxelRecord) == 32);

  /// fire() when the model has no wall particles (rdme_fire.cpp).
  std::uint32_t fire_open(std::uint32_t i, double u);
  void apply_reaction_open(std::size_t r, std::uint32_t i) {
    for (const auto& [s, delta] : table_.reaction(r).change) {
      counts_[static_cast<std::size_t>(s) * n_ + i] += delta;
    }
    if (!law_readers_.empty()) {
      for (const auto& [s, delta] : table_.reaction(r).change) refresh_laws(s, i);
    }
  }
  /// Recomputes the cached propensities of the rate laws that read species s in
  /// voxel i (law_readers_[s]): after an event changed X_si, only those can change.
  void refresh_laws(int s, std::uint32_t i) {
    if (law_readers_.empty()) return;
    const std::size_t nl = table_.law_count();
    for (const int k : law_readers_[s]) {
      law_a_[i * nl + k] = table_.propensity(table_.law_reaction(k), i, counts_.data(), n_);
    }
  }
  /// Recomputes every cached rate-law propensity (counts or volumes set wholesale).
  void refresh_all_laws();
  void assign_reservoir_concentrations();
  void assign_free_walls();
  /// Out-edge of i picked by the residual v for a species with free walls.
  [[nodiscard]] std::uint32_t free_edge(int s, std::uint32_t i, double v) const;
  void compute_free_sums();

  Model model_;
  DiffusionGraph graph_;
  GraphBuilder builder_;
  ReactionTable table_;
  // Huge pages: the event loop reads both at random (event_heap.hpp).
  std::vector<VoxelRecord, detail::HugePageAllocator<VoxelRecord>> voxels_;
  ParticleState inputs_;
  std::vector<std::int64_t, detail::HugePageAllocator<std::int64_t>> counts_;
  std::vector<double> kappa_;
  std::vector<int> diffusing_;
  std::vector<std::uint8_t> reservoir_;  ///< per species: has a WallReservoir
  std::vector<double> reservoir_conc_;   ///< per (species, voxel), species-major, walls only
  std::vector<int> free_slot_;           ///< per species: slot in free_mask_/free_sum_, or -1
  std::vector<std::uint8_t> free_mask_;  ///< per (slot, voxel): 1 all-walls free, 2 listed free
  std::vector<double> free_sum_;         ///< per (slot, voxel): jump_weight_sum()
  std::size_t n_ = 0;
  bool has_walls_ = false;
  /// Rate-law propensities [voxel * law_count + law] and, per species, the laws
  /// that read it (empty when the model has no rate law).
  std::vector<double> law_a_;
  std::vector<std::vector<int>> law_readers_;
};

}  // namespace sadr::ssa
