// SPDX-License-Identifier: MIT
// NsmSolver::save / restore. Layout (version 1, little-endian):
//   "SADRNSM1" | u32 version | u64 model fingerprint | u64 seed | 4 x u64 RNG state
//   | f64 time | u64 events | i32 dimension | vec<f64> positions | vec<f64> densities
//   | vec<f64> masses | vec<u8> kinds | vec<i64> counts (species-major)
//   | vec<{f64 time, u32 voxel}> heap entries in heap order | u64 FNV-1a of all previous bytes
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
  w.pod(kSnapshotVersion);
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
  std::vector<HeapRecord> heap;
  for (const auto& e : heap_.entries()) heap.push_back({e.time, e.voxel, 0});
  w.vec(heap);
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
  if (version != kSnapshotVersion) {
    throw InvalidArgument("snapshot: version = " + std::to_string(version) +
                          " (supported: " + std::to_string(kSnapshotVersion) + ")");
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
  auto heap = r.vec<HeapRecord>("heap", max_len);
  if (r.remaining() != 8) throw InvalidArgument("snapshot: unexpected trailing bytes");

  RdmeState fresh(state_.model());
  if (!in.densities.empty()) fresh.update_graph(in);
  fresh.restore_counts(std::move(counts));
  std::vector<EventHeap4::Entry> entries;
  entries.reserve(heap.size());
  for (const auto& h : heap) entries.push_back({h.time, h.voxel});
  if (entries.size() != fresh.voxel_count()) {
    throw InvalidArgument("snapshot: heap has " + std::to_string(entries.size()) +
                          " entries, expected " + std::to_string(fresh.voxel_count()));
  }
  EventHeap4 fresh_heap;
  fresh_heap.assign_entries(entries);
  // Commit (strong guarantee: nothing above touched *this).
  state_ = std::move(fresh);
  heap_ = std::move(fresh_heap);
  for (std::size_t i = 0; i < state_.voxel_count(); ++i) {
    const auto v = static_cast<std::uint32_t>(i);
    state_.cached_rate(v) = state_.total_rate(v);
  }
  rng_.set_state(rng_state);
  seed_ = seed;
  time_ = time;
  events_ = events;
}

}  // namespace sadr::ssa
