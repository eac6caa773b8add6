// SPDX-License-Identifier: MIT
// parallel_for over [0, n) in contiguous chunks on std::threads; each index is written by one
// thread only, so results do not depend on the thread count (private header).
#pragma once

#include <algorithm>
#include <cstddef>
#include <thread>
#include <vector>

namespace sadr::geometry {

inline int resolve_threads(int threads) {
  if (threads > 0) return threads;
  return std::max(1u, std::thread::hardware_concurrency());
}

template <class F>
void parallel_for(std::size_t n, int threads, F&& f) {
  const std::size_t t =
      std::min<std::size_t>(resolve_threads(threads), std::max<std::size_t>(n, 1));
  if (t <= 1) {
    for (std::size_t i = 0; i < n; ++i) f(i);
    return;
  }
  // Interleaved chunks of 64 balance work that varies along the index range.
  constexpr std::size_t kChunk = 64;
  std::vector<std::thread> pool;
  for (std::size_t w = 0; w < t; ++w) {
    pool.emplace_back([&, w] {
      for (std::size_t c = w * kChunk; c < n; c += t * kChunk) {
        for (std::size_t i = c; i < std::min(n, c + kChunk); ++i) f(i);
      }
    });
  }
  for (auto& th : pool) th.join();
}

}  // namespace sadr::geometry
