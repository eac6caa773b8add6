// SPDX-License-Identifier: MIT
#include "sadr/ssa/event_heap.hpp"

#include <algorithm>
#include <limits>
#include <string>

#include "sadr/common/status.hpp"

namespace sadr::ssa {

void EventHeap4::allocate(std::size_t n) {
  if (n != n_ || !data_) {
    data_.reset(static_cast<Entry*>(
        ::operator new[]((n + kOffset + 4) * sizeof(Entry), std::align_val_t{64})));
  }
  n_ = n;
  pos_.resize(n);
  // Sentinels (sift_down() reads four children slots of every internal node).
  for (std::size_t k = n; k < n + 4; ++k) {
    at(k) =
        Entry{std::numeric_limits<double>::infinity(), std::numeric_limits<std::uint32_t>::max()};
  }
}

EventHeap4& EventHeap4::operator=(const EventHeap4& other) {
  if (this == &other) return *this;
  allocate(other.n_);
  if (n_ > 0) std::copy(other.data_.get(), other.data_.get() + n_ + kOffset + 4, data_.get());
  pos_ = other.pos_;
  return *this;
}

void EventHeap4::assign(std::span<const double> times) {
  allocate(times.size());
  for (std::size_t i = 0; i < n_; ++i) {
    at(i) = Entry{times[i], static_cast<std::uint32_t>(i)};
    pos_[i] = static_cast<std::uint32_t>(i);
  }
  if (n_ < 2) return;
  for (std::size_t k = (n_ - 2) / 4 + 1; k-- > 0;) sift_down(k, at(k));
}

void EventHeap4::assign_entries(std::span<const Entry> entries) {
  allocate(entries.size());
  std::vector<std::uint8_t> seen(n_, 0);
  for (std::size_t k = 0; k < n_; ++k) {
    const Entry& e = entries[k];
    if (e.voxel >= n_ || seen[e.voxel]) {
      throw InvalidArgument("event heap: entry " + std::to_string(k) + " has voxel " +
                            std::to_string(e.voxel) + " (duplicate or >= " + std::to_string(n_) +
                            ")");
    }
    seen[e.voxel] = 1;
    at(k) = e;
    pos_[e.voxel] = static_cast<std::uint32_t>(k);
  }
  if (!valid()) throw InvalidArgument("event heap: stored entries violate the heap order");
}

std::vector<EventHeap4::Entry> EventHeap4::entries() const {
  std::vector<Entry> out(n_);
  for (std::size_t k = 0; k < n_; ++k) out[k] = at(k);
  return out;
}

bool EventHeap4::valid() const {
  for (std::size_t k = 0; k < n_; ++k) {
    if (pos_[at(k).voxel] != k) return false;
    if (k > 0 && at(k).time < at((k - 1) / 4).time) return false;
  }
  return true;
}

}  // namespace sadr::ssa
