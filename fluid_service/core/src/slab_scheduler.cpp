// SPDX-License-Identifier: MIT
/// \file slab_scheduler.cpp
/// SlabScheduler (see slab_scheduler.hpp): the slab partition, its work split, the point-to-point
/// waits, and the SDPD binning with the forward filter of a full list.
#include "sadr/fluid/slab_scheduler.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <thread>

#include "sadr/common/status.hpp"

namespace sadr::fluid {

void SlabScheduler::set(SlabPartition&& partition, const NeighborList& forward) {
  part_ = std::move(partition);
  if (done_count_ != part_.count) {
    done_ = std::make_unique<std::atomic<std::uint32_t>[]>(part_.count);
    for (std::uint32_t s = 0; s < part_.count; ++s) done_[s].store(0);
    done_count_ = part_.count;
  }
  // Work per slab (its members plus their forward entries), prefix-summed per colour: a slab
  // holds one or two lattice rows/layers (width ~0.58 cutoff), so equal slab counts per thread
  // are not equal work.
  for (std::uint32_t c = 0; c < kColours; ++c) {
    auto& w = colour_work_[c];
    w.assign(1, 0);
    for (std::uint32_t s = c; s < part_.count; s += kColours) {
      std::uint64_t work = part_.start[s + 1] - part_.start[s];
      for (std::uint32_t k = part_.start[s]; k < part_.start[s + 1]; ++k)
        work += forward.of(part_.members[k]).size();
      w.push_back(w.back() + work);
    }
  }
}

void SlabScheduler::partition_and_filter(const PeriodicBox& box, int axis, double cutoff,
                                         std::span<const double> x, NeighborList& list) {
  // kReach = 2 rather than 1: 3D, 1e4 particles gives 12 slabs (4 per colour) instead of 6
  // (3 per colour, which caps 2 threads at 1.5x).
  const double len = box.length(axis);
  // (1 + 1e-9): a listed pair stays within kReach slabs despite rounding in the binning
  auto ns = static_cast<std::uint32_t>(std::floor(kReach * len / (cutoff * (1.0 + 1e-9))));
  SlabPartition p;
  p.wrap = box.periodic(axis);
  if (p.wrap) {
    ns -= ns % kColours;
    if (ns <= 2 * kReach) ns = 1;  // slabs +1, +2 would alias -2, -1: one slab (serial, exact)
  }
  p.count = std::max<std::uint32_t>(ns, 1);
  const double lo = box.box().lo[axis], inv_w = p.count / len;
  const std::size_t n = x.size() / 3;
  std::vector<std::uint32_t> slab_of(n);
  p.start.assign(p.count + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = std::floor((x[3 * i + axis] - lo) * inv_w);
    const auto s = static_cast<std::uint32_t>(std::clamp(t, 0.0, p.count - 1.0));
    slab_of[i] = s;
    ++p.start[s + 1];
  }
  for (std::uint32_t s = 0; s < p.count; ++s) p.start[s + 1] += p.start[s];
  p.members.resize(n);
  std::vector<std::uint32_t> fill(p.start.begin(), p.start.end() - 1);
  for (std::size_t i = 0; i < n; ++i) p.members[fill[slab_of[i]]++] = static_cast<std::uint32_t>(i);
  // Keep only the forward pairs, in place: every pair is listed once, which halves the entries
  // the pair loops read (and they need no slab test per entry).
  std::uint32_t out = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t s = slab_of[i];
    const std::uint32_t begin = list.offsets[i], end = list.offsets[i + 1];
    list.offsets[i] = out;
    for (std::uint32_t k = begin; k < end; ++k) {
      const std::uint32_t j = list.indices[k];
      // slab distance forward (mod the count on a periodic axis; "negative" is huge unsigned)
      std::uint32_t ds = slab_of[j] - s;
      if (p.wrap && slab_of[j] < s) ds += p.count;
      if (ds == 0 ? j > i : ds <= kReach) list.indices[out++] = j;
    }
  }
  // The full list is symmetric, so exactly half of it must remain (no pair lost or doubled).
  if (2 * static_cast<std::size_t>(out) != list.indices.size()) {
    throw NumericalFailure("slab filter kept " + std::to_string(out) + " of " +
                               std::to_string(list.indices.size()) + " list entries (internal)",
                           {{"quantity", "neighbour list"}});
  }
  list.offsets[n] = out;
  // No shrink_to_fit: its copy would hold the half list beside the full one, the process peak
  // (issue 20); the next build releases this block before it allocates.
  list.indices.resize(out);
  set(std::move(p), list);
}

void SlabScheduler::wait_done(std::uint32_t s) const {
  for (int spin = 0; done_[s].load(std::memory_order_acquire) != epoch_; ++spin) {
    if (spin < 4096) {
#if defined(__x86_64__) || defined(__i386__)
      __builtin_ia32_pause();
#endif
    } else {
      std::this_thread::yield();
    }
  }
}

std::uint32_t SlabScheduler::slab_at(std::uint32_t s, std::int64_t o) const {
  const std::int64_t q = static_cast<std::int64_t>(s) + o;
  const auto n = static_cast<std::int64_t>(part_.count);
  if (part_.wrap) return static_cast<std::uint32_t>((q + n) % n);
  return q < 0 || q >= n ? part_.count : static_cast<std::uint32_t>(q);
}

// Contiguous (about the same part of the box in every phase, so a thread's particle data stays
// in its core's cache), cut by work: slab k goes to the thread whose share holds the middle of
// its work. The result does not depend on the assignment (each particle's sums keep the
// slab/member order).
std::pair<std::uint64_t, std::uint64_t> SlabScheduler::own_run(std::uint32_t phase,
                                                               std::uint64_t nt,
                                                               std::uint64_t t) const {
  const std::vector<std::uint64_t>& w = colour_work_[phase];
  const std::uint64_t tasks = w.size() - 1, total = w.back();
  auto owner = [&](std::uint64_t k) {
    const std::uint64_t o = total > 0 ? (w[k] + w[k + 1]) * nt / (2 * total) : k * nt / tasks;
    return std::min(o, nt - 1);
  };
  std::uint64_t k0 = 0;
  while (k0 < tasks && owner(k0) < t) ++k0;
  std::uint64_t k1 = k0;
  while (k1 < tasks && owner(k1) == t) ++k1;
  return {k0, k1};
}

std::size_t SlabScheduler::bytes() const {
  std::size_t b = (part_.start.capacity() + part_.members.capacity()) * sizeof(std::uint32_t);
  for (const auto& w : colour_work_) b += w.capacity() * sizeof(std::uint64_t);
  return b + done_count_ * sizeof(std::atomic<std::uint32_t>);
}

}  // namespace sadr::fluid
