// SPDX-License-Identifier: MIT
/// \file reorder_buffer.hpp
/// Items that complete in any order, handed on in index order 0, 1, 2, ...:
/// the realizations of an ensemble finish in any order but are added to the
/// ensemble in index order, so that its floating-point sums (and files) are
/// reproducible. Not thread-safe: the caller holds a lock around complete().
#pragma once

#include <functional>
#include <map>
#include <utility>

namespace sadr::orchestrator {

template <class T>
class ReorderBuffer {
 public:
  /// `sink(index, item)` receives the items in index order.
  explicit ReorderBuffer(std::function<void(int, T&)> sink) : sink_(std::move(sink)) {}

  /// Item `index` is complete: hands it on with every waiting one after it, as
  /// far as the indices are contiguous.
  void complete(int index, T item) {
    pending_.emplace(index, std::move(item));
    for (auto it = pending_.find(next_); it != pending_.end(); it = pending_.find(++next_)) {
      sink_(it->first, it->second);
      pending_.erase(it);
    }
  }
  /// The first index not handed on yet.
  [[nodiscard]] int next() const { return next_; }
  /// Items complete but waiting for an earlier one.
  [[nodiscard]] std::size_t waiting() const { return pending_.size(); }

 private:
  std::function<void(int, T&)> sink_;
  std::map<int, T> pending_;
  int next_ = 0;
};

}  // namespace sadr::orchestrator
