// SPDX-License-Identifier: MIT
/// \file slab_scheduler.hpp
/// The slab scheduler of the half-pair loops (SDPD's bulk path and tDPD): every pair is
/// evaluated once and written to both particles, in parallel, without atomics and with results
/// independent of the thread count (docs/fluid-core.md section 3).
///
/// Particles are binned into slabs along one axis, each at least (list cutoff) / kReach wide,
/// so a listed pair spans at most kReach + 1 consecutive slabs. The list is a "forward" list:
/// j in the same slab with j > i, or j 1..kReach slabs ahead (mod the slab count on a periodic
/// axis, where the count is a multiple of kColours = kReach + 1 above 2 kReach, else 1). Phase
/// p runs the slabs s = p mod kColours; slab s writes only to slabs s..s+kReach, so no two
/// threads write the same particle, and each particle receives its contributions in an order
/// fixed by (phase, slab, member): independent of the thread count. There is no barrier between
/// the phases: a slab waits (release/acquire flags holding the pass number) only for the slabs
/// of earlier phases within kReach of it, the ones whose writes it must follow.
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "sadr/fluid/neighbor_list.hpp"
#include "sadr/fluid/parallel.hpp"

namespace sadr::fluid {

/// Particles binned into slabs along one axis (CSR: the members of slab s are
/// members[start[s] .. start[s + 1])).
struct SlabPartition {
  std::uint32_t count = 1;
  bool wrap = false;  ///< the slab axis is periodic (slab count - 1 neighbours slab 0)
  std::vector<std::uint32_t> start{0, 0};
  std::vector<std::uint32_t> members;
};

/// A callback on the members [first, last) of one slab, without a template (the fused SDPD
/// sub-step passes one from another translation unit; one indirect call per slab).
class SlabMembersFn {
 public:
  SlabMembersFn() = default;
  template <class F>
  explicit SlabMembersFn(F& f)
      : ctx_(&f), fn_([](void* c, const std::uint32_t* a, const std::uint32_t* b) {
          (*static_cast<F*>(c))(a, b);
        }) {}
  explicit operator bool() const { return fn_ != nullptr; }
  void operator()(const std::uint32_t* first, const std::uint32_t* last) const {
    fn_(ctx_, first, last);
  }

 private:
  void* ctx_ = nullptr;
  void (*fn_)(void*, const std::uint32_t*, const std::uint32_t*) = nullptr;
};

class SlabScheduler {
 public:
  static constexpr std::uint32_t kReach = 2;  ///< slab width >= list cutoff / kReach
  static constexpr std::uint32_t kColours = kReach + 1;

  [[nodiscard]] const SlabPartition& partition() const { return part_; }
  [[nodiscard]] std::uint32_t count() const { return part_.count; }
  /// Sets the slabs (of the forward list `forward`): the per-colour work prefix sums for the
  /// work-balanced split among threads, and the done flags.
  void set(SlabPartition&& partition, const NeighborList& forward);
  /// Bins the positions x (3N) into slabs along `axis` of `box` and filters the full list
  /// `list` (cutoff `cutoff`) in place to its forward pairs; then set(). Throws
  /// NumericalFailure if the filter does not keep exactly half of the list (internal).
  void partition_and_filter(const PeriodicBox& box, int axis, double cutoff,
                            std::span<const double> x, NeighborList& list);
  /// Before each parallel region that calls run_team().
  void next_pass() {
    if (++epoch_ == 0) epoch_ = 1;
  }
  /// Called by every thread of an enclosing parallel region (or outside one): each thread takes
  /// a contiguous, work-balanced run of the slabs of a phase and calls per_slab(first, last, t)
  /// (t: its thread index) on the members of each. Then, if `after` is set, after(first, last)
  /// runs on the members of each of the thread's slabs once every slab writing to them is done.
  /// No barrier at the end.
  template <class PerSlab>
  void run_team(PerSlab&& per_slab, SlabMembersFn after = {});
  /// next_pass() and run_team() in a parallel region of its own (serial unless `parallel`).
  template <class PerSlab>
  void run(PerSlab&& per_slab, [[maybe_unused]] bool parallel) {
    next_pass();
#ifdef SADR_HAVE_OPENMP  // (a header: no unknown-pragma warning where OpenMP is off)
#pragma omp parallel if (parallel)
#endif
    run_team(per_slab);
  }
  /// Heap bytes held (benchmark diagnostics).
  [[nodiscard]] std::size_t bytes() const;

 private:
  void wait_done(std::uint32_t s) const;
  /// The slab at offset o in [-kReach, kReach] from s, or count() if none (walled axis).
  [[nodiscard]] std::uint32_t slab_at(std::uint32_t s, std::int64_t o) const;
  /// The run [k0, k1) of the phase's slabs owned by thread t of nt.
  [[nodiscard]] std::pair<std::uint64_t, std::uint64_t> own_run(std::uint32_t phase,
                                                                std::uint64_t nt,
                                                                std::uint64_t t) const;

  SlabPartition part_;
  /// Per colour: prefix sums of the work (members + forward list entries) of its slabs.
  std::array<std::vector<std::uint64_t>, kColours> colour_work_;
  /// Per slab: the number of the last pass that has finished it.
  std::unique_ptr<std::atomic<std::uint32_t>[]> done_;
  std::uint32_t done_count_ = 0;
  std::uint32_t epoch_ = 0;  ///< the current pass (never 0)
};

template <class PerSlab>
void SlabScheduler::run_team(PerSlab&& per_slab, SlabMembersFn after) {
  const auto nt = static_cast<std::uint64_t>(team_size());
  const auto t = static_cast<std::uint64_t>(thread_index());
  const std::uint32_t n_slabs = part_.count;
  auto members = [&](std::uint32_t s) {
    return std::pair<const std::uint32_t*, const std::uint32_t*>{
        part_.members.data() + part_.start[s], part_.members.data() + part_.start[s + 1]};
  };
  // The two ends of a run (next to other threads' slabs) go first: the other threads wait for
  // them.
  auto each_end_first = [](std::uint64_t k0, std::uint64_t k1, auto&& f) {
    if (k1 > k0) f(k0);
    if (k1 > k0 + 1) f(k1 - 1);
    for (std::uint64_t k = k0 + 1; k + 1 < k1; ++k) f(k);
  };
  for (std::uint32_t phase = 0; phase < kColours; ++phase) {
    const auto [k0, k1] = own_run(phase, nt, t);
    each_end_first(k0, k1, [&](std::uint64_t k) {
      const auto s = static_cast<std::uint32_t>(phase + kColours * k);
      if (nt > 1) {
        for (std::int64_t o = -static_cast<std::int64_t>(kReach); o <= kReach; ++o) {
          const std::uint32_t q = slab_at(s, o);
          if (o != 0 && q < n_slabs && q % kColours < phase) wait_done(q);
        }
      }
      const auto [first, last] = members(s);
      per_slab(first, last, static_cast<std::size_t>(t));
      done_[s].store(epoch_, std::memory_order_release);
    });
  }
  if (!after) return;
  // after(first, last) on the members of each own slab q once its writers q-R..q are done
  // (nobody reads or writes its particles' entries afterwards in this pass). The interior of
  // the runs first, the ends (which may wait for other threads) last.
  for (int pass = 0; pass < 2; ++pass) {
    for (std::uint32_t phase = 0; phase < kColours; ++phase) {
      const auto [k0, k1] = own_run(phase, nt, t);
      for (std::uint64_t k = k0; k < k1; ++k) {
        const bool end = k == k0 || k + 1 == k1;
        if (end != (pass == 1)) continue;
        const auto s = static_cast<std::uint32_t>(phase + kColours * k);
        if (nt > 1) {
          for (std::int64_t o = -static_cast<std::int64_t>(kReach); o < 0; ++o) {
            const std::uint32_t q = slab_at(s, o);
            if (q < n_slabs) wait_done(q);
          }
        }
        const auto [first, last] = members(s);
        after(first, last);
      }
    }
  }
}

}  // namespace sadr::fluid
