// SPDX-License-Identifier: MIT
#include "heap_counter.hpp"

#include <malloc.h>

#include <atomic>
#include <cstdlib>
#include <new>

namespace {

std::atomic<long long> g_live{0}, g_peak{0};

void* counted_alloc(std::size_t n) {
  void* p = std::malloc(n == 0 ? 1 : n);
  if (!p) throw std::bad_alloc();
  const auto sz = static_cast<long long>(malloc_usable_size(p));
  const long long now = g_live.fetch_add(sz) + sz;
  long long pk = g_peak.load();
  while (now > pk && !g_peak.compare_exchange_weak(pk, now)) {
  }
  return p;
}

void counted_free(void* p) noexcept {
  if (!p) return;
  g_live.fetch_sub(static_cast<long long>(malloc_usable_size(p)));
  std::free(p);
}

}  // namespace

namespace sadr::bench {
long long heap_live() {
  return g_live.load();
}
long long heap_peak() {
  return g_peak.load();
}
void heap_reset_peak() {
  g_peak = g_live.load();
}
}  // namespace sadr::bench

void* operator new(std::size_t n) {
  return counted_alloc(n);
}
void* operator new[](std::size_t n) {
  return counted_alloc(n);
}
void operator delete(void* p) noexcept {
  counted_free(p);
}
void operator delete[](void* p) noexcept {
  counted_free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  counted_free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  counted_free(p);
}
