// SPDX-License-Identifier: MIT
// NsmSolver::save / restore. Layout (version 2, little-endian):
//   "SADRNSM1" | u32 version | u64 model fingerprint | u64 seed | 4 x u64 RNG state
//   | f64 time | u64 events | i32 dimension | vec<f64> positions | vec<f64> densities
//   | vec<f64> masses | vec<u8> kinds | vec<i64> counts (species-major)
//   | vec<f64> next event time by voxel
//   | [only with laws of t or frozen species: f64 input time | vec<f64> frozen]
//   | [version 3 (adaptive models) only: 4 x u64 leap RNG state | u64 molecules leaped]
//   | u64 FNV-1a of all previous bytes
// Version 1 (written by the 4-ary heap solver) stored the last field as
// vec<{f64 time, u32 voxel, u32 pad}> in heap order: the same times, permuted;
// restore() still reads it. The event queue is a function of the times alone
// (EventTree), so the times are all a snapshot needs.
#include <cmath>
#include <string>

#include "blob.hpp"
#include "sadr/common/status.hpp"
#include "sadr/ssa/nsm_solver.hpp"

namespace sadr::ssa {

namespace {
constexpr std::string_view kMagic = "SADRNSM1";
struct HeapRecord {
  double time;
  std::uint32_t voxel;
  std::uint32_t pad;
};
}  // namespace

std::string NsmSolver::save() const {
  detail::BlobWriter w;
  w.bytes(kMagic);
  w.pod(leap_ ? kAdaptiveSnapshotVersion : kSnapshotVersion);
  w.pod(state_.model().fingerprint());
  w.pod(seed_);
  w.pod(rng_.state());
  w.pod(time_);
  w.pod(events_);
  const ParticleState& in = state_.graph_inputs();
  w.pod(static_cast<std::int32_t>(in.dimension));
  w.vec(in.positions);
  w.vec(in.densities);
  w.vec(in.masses);
  w.vec(in.kinds);
  w.vec(state_.all_counts());
  w.vec(queue_.times());
  if (state_.reactions().has_external_laws()) {  // the inputs the cached rates were made with
    w.pod(state_.input_time());
    w.vec(state_.frozen());
  }
  if (leap_) {  // version 3: the leap stream (no window state: every window ends in advance())
    w.pod(leap_->rng_state());
    w.pod(leap_->moved());
  }
  const std::uint64_t sum = detail::fnv1a(w.str());
  w.pod(sum);
  return w.str();
}

void NsmSolver::restore(std::string_view blob) {
  detail::BlobReader r(blob);
  if (r.bytes(kMagic.size(), "magic") != kMagic) {
    throw InvalidArgument("snapshot: bad magic (not an NsmSolver snapshot)");
  }
  const auto version = r.pod<std::uint32_t>("version");
  if (version != 1 && version != kSnapshotVersion && version != kAdaptiveSnapshotVersion) {
    throw InvalidArgument("snapshot: version = " + std::to_string(version) + " (supported: 1, " +
                          std::to_string(kSnapshotVersion) + ", " +
                          std::to_string(kAdaptiveSnapshotVersion) + ")");
  }
  if ((version == kAdaptiveSnapshotVersion) != leap_.has_value()) {
    throw InvalidArgument("snapshot: version = " + std::to_string(version) +
                          (leap_ ? " into an adaptive solver (allowed: 3)"
                                 : " into an exact solver (allowed: 1, 2)"));
  }
  if (blob.size() < 8) throw InvalidArgument("snapshot truncated");
  const std::string_view body = blob.substr(0, blob.size() - 8);
  {
    detail::BlobReader tail(blob.substr(blob.size() - 8));
    if (tail.pod<std::uint64_t>("checksum") != detail::fnv1a(body)) {
      throw InvalidArgument("snapshot: checksum mismatch (corrupt or truncated blob)");
    }
  }
  const auto fingerprint = r.pod<std::uint64_t>("model fingerprint");
  if (fingerprint != state_.model().fingerprint()) {
    throw InvalidArgument("snapshot: made with another model (fingerprint differs)");
  }
  const auto seed = r.pod<std::uint64_t>("seed");
  const auto rng_state = r.pod<rng::Xoshiro256::State>("rng state");
  const auto time = r.pod<double>("time");
  const auto events = r.pod<std::uint64_t>("events");
  ParticleState in;
  in.dimension = r.pod<std::int32_t>("dimension");
  const std::uint64_t max_len = blob.size();
  in.positions = r.vec<double>("positions", max_len);
  in.densities = r.vec<double>("densities", max_len);
  in.masses = r.vec<double>("masses", max_len);
  in.kinds = r.vec<ParticleKind>("kinds", max_len);
  auto counts = r.vec<std::int64_t>("counts", max_len);
  std::vector<double> times;
  if (version == 1) {
    // Heap entries in heap order: scatter them by voxel, each voxel exactly once.
    const auto heap = r.vec<HeapRecord>("heap", max_len);
    times.assign(heap.size(), 0.0);
    std::vector<std::uint8_t> seen(heap.size(), 0);
    for (std::size_t k = 0; k < heap.size(); ++k) {
      const std::uint32_t v = heap[k].voxel;
      if (v >= heap.size() || seen[v]) {
        throw InvalidArgument("snapshot: heap entry " + std::to_string(k) + " has voxel " +
                              std::to_string(v) +
                              " (duplicate or >= " + std::to_string(heap.size()) + ")");
      }
      seen[v] = 1;
      times[v] = heap[k].time;
    }
  } else {
    times = r.vec<double>("event times", max_len);
  }
  RdmeState fresh(state_.model());
  if (!in.densities.empty()) fresh.update_graph(in);
  double input_time = 0;
  std::vector<double> frozen;
  const bool external = fresh.has_graph() && fresh.reactions().has_external_laws();
  if (external) {
    input_time = r.pod<double>("input time");
    frozen = r.vec<double>("frozen concentrations", max_len);
  }
  rng::Xoshiro256::State leap_state{};
  std::uint64_t leap_moved = 0;
  if (version == kAdaptiveSnapshotVersion) {
    leap_state = r.pod<rng::Xoshiro256::State>("leap rng state");
    leap_moved = r.pod<std::uint64_t>("leaped molecules");
  }
  if (r.remaining() != 8) throw InvalidArgument("snapshot: unexpected trailing bytes");
  for (std::size_t v = 0; v < times.size(); ++v) {
    if (std::isnan(times[v]) || times[v] < time) {
      throw InvalidArgument("snapshot: event time of voxel " + std::to_string(v) + " = " +
                            format_value(times[v]) + " (allowed: >= the clock " +
                            format_value(time) + ")");
    }
  }

  if (external) fresh.set_inputs(input_time, frozen);
  fresh.restore_counts(std::move(counts));
  if (times.size() != fresh.voxel_count()) {
    throw InvalidArgument("snapshot: " + std::to_string(times.size()) + " event times, expected " +
                          std::to_string(fresh.voxel_count()));
  }
  EventTree fresh_queue;
  fresh_queue.assign(times);
  // Commit (strong guarantee: nothing above touched *this).
  state_ = std::move(fresh);
  queue_ = std::move(fresh_queue);
  for (std::size_t i = 0; i < state_.voxel_count(); ++i) {
    const auto v = static_cast<std::uint32_t>(i);
    state_.cached_rate(v) = state_.total_rate(v);
  }
  rng_.set_state(rng_state);
  seed_ = seed;
  time_ = time;
  events_ = events;
  if (leap_) leap_->restore(leap_state, leap_moved);
}

}  // namespace sadr::ssa
