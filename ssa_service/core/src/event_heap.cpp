// SPDX-License-Identifier: MIT
#include "sadr/ssa/event_heap.hpp"

#include <algorithm>
#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif
#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define SADR_EVENT_TREE_AVX512 1
#endif

namespace sadr::ssa {

namespace detail {

namespace {
constexpr std::size_t kHugePage = std::size_t{2} << 20;
constexpr std::size_t kHugeMin = std::size_t{1} << 18;  // smaller: mostly empty huge page
#if defined(__linux__) && defined(MADV_HUGEPAGE)
constexpr bool kUseMmap = true;
#else
constexpr bool kUseMmap = false;
#endif
std::size_t round_up(std::size_t bytes) {
  return (bytes + kHugePage - 1) & ~(kHugePage - 1);
}
}  // namespace

void* allocate_huge(std::size_t bytes) {
  if (!kUseMmap || bytes < kHugeMin) return ::operator new (bytes, std::align_val_t{64});
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  const std::size_t len = round_up(bytes);
  void* raw =
      mmap(nullptr, len + kHugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (raw == MAP_FAILED) throw std::bad_alloc();
  // Keep a 2 MiB-aligned window of len bytes, unmap the rest.
  const auto a = reinterpret_cast<std::uintptr_t>(raw);
  const std::uintptr_t lo = (a + kHugePage - 1) & ~(kHugePage - 1);
  if (lo > a) munmap(raw, lo - a);
  const std::uintptr_t end = a + len + kHugePage;
  if (end > lo + len) munmap(reinterpret_cast<void*>(lo + len), end - (lo + len));
  void* p = reinterpret_cast<void*>(lo);
  (void)madvise(p, len, MADV_HUGEPAGE);
  return p;
#endif
}

void free_huge(void* p, std::size_t bytes) {
  if (p == nullptr) return;
  if (!kUseMmap || bytes < kHugeMin) {
    ::operator delete (p, std::align_val_t{64});
    return;
  }
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  munmap(p, round_up(bytes));
#endif
}

}  // namespace detail

namespace {
std::size_t padded(std::size_t count) {
  return (count + EventTree::kFan - 1) / EventTree::kFan * EventTree::kFan;
}
}  // namespace

void EventTree::assign(std::span<const double> times) {
  n_ = times.size();
  depth_ = 0;
  sib_valid_ = false;
  min_.clear();
  arg_.clear();
  if (n_ == 0) return;
  // Level sizes N, ceil(N / kFan), ..., 1: at least one level above the times.
  std::size_t counts[kMaxDepth + 1] = {n_};
  do {
    ++depth_;
    counts[depth_] = (counts[depth_ - 1] + kFan - 1) / kFan;
  } while (counts[depth_] > 1);
  std::size_t mins = 0, args = 0;
  for (std::size_t L = 0; L <= depth_; ++L) {
    min_off_[L] = mins;
    arg_off_[L] = args;
    mins += padded(counts[L]);
    if (L > 0) args += padded(counts[L]);
  }
  min_.assign(mins, kInf);  // padding never wins (ties go to the lowest index)
  arg_.assign(args, 0);
  std::copy(times.begin(), times.end(), min_.begin());
  for (std::size_t L = 1; L <= depth_; ++L) {
    for (std::size_t k = 0; k < counts[L]; ++k) recompute(L, k);
  }
}

template <unsigned (*Argmin)(const double*, std::size_t, double, double*)>
void EventTree::update_top_with(double time) {
  // The new minimum of level L is min(siblings' minimum, the child's new minimum):
  // computing the siblings' minima first, for all levels (independent work: their
  // loads overlap), leaves a chain of one compare per level. Recomputing each
  // level from the one below put a full SIMD reduction per level on the critical
  // path. Loads also precede the stores into the same lines: a wide load of a line
  // with a pending narrow store to it would wait for the store (no forwarding).
  const std::uint32_t top = top_voxel();
  if (!sib_valid_ || sib_top_ != top) sibling_minima<Argmin>(top);
  sib_valid_ = false;  // the path's lines change below
  const double* sib_min = sib_min_;
  const unsigned* sib_lane = sib_lane_;
  const std::uint32_t* sib_arg = sib_arg_;
  std::size_t child = top;
  double value = time;
  std::uint32_t arg = top;
  for (std::size_t L = 1; L <= depth_; ++L) {
    const std::size_t lane = child & (kFan - 1);
    min_[min_off_[L - 1] + child] = value;
    // Ties go to the lower index: a sibling left of the child wins them.
    const bool sibling = sib_min[L] < value || (sib_min[L] == value && sib_lane[L] < lane);
    value = sibling ? sib_min[L] : value;
    arg = sibling ? sib_arg[L] : arg;
    child >>= kShift;
    arg_[arg_off_[L] + child] = arg;
  }
  min_[min_off_[depth_]] = value;
}

template <unsigned (*Argmin)(const double*, std::size_t, double, double*)>
void EventTree::sibling_minima(std::uint32_t top) {
  std::size_t child = top;
  for (std::size_t L = 1; L <= depth_; ++L) {
    const double* line = min_.data() + min_off_[L - 1] + (child & ~(kFan - 1));
    const unsigned k = Argmin(line, child & (kFan - 1), kInf, &sib_min_[L]);
    child >>= kShift;
    sib_lane_[L] = k;
    // (k may be the child's own lane when every sibling is +inf: never chosen.)
    sib_arg_[L] = L == 1 ? static_cast<std::uint32_t>((child << kShift) + k)
                         : arg_[arg_off_[L - 1] + (child << kShift) + k];
  }
  sib_top_ = top;
  sib_valid_ = true;
}

template <unsigned (*Argmin)(const double*, std::size_t, double, double*)>
std::uint32_t EventTree::runner_up_with() {
  // The minimum of the top's sibling minima (its own lane read as +inf on every
  // level), combined with branch-free selects (a compare-and-branch per level
  // mispredicted often: measured). Ties: the lower voxel index (all +inf: the top).
  const std::uint32_t top = top_voxel();
  if (!sib_valid_ || sib_top_ != top) sibling_minima<Argmin>(top);
  double best = kInf;
  std::uint32_t best_arg = top;
  for (std::size_t L = depth_; L >= 1; --L) {
    const bool take =
        sib_min_[L] < best || (sib_min_[L] == best && best < kInf && sib_arg_[L] < best_arg);
    best = take ? sib_min_[L] : best;
    best_arg = take ? sib_arg_[L] : best_arg;
  }
  return best_arg;
}

#if SADR_EVENT_TREE_AVX512
namespace {
// argmin_line_with() in AVX-512: one load, a masked move for the substitution,
// a 3-step reduction and one compare into a mask (~15 instructions instead of
// ~60 with SSE2; update_top() runs one per tree level per event).
__attribute__((target("avx512f"))) unsigned argmin_line_avx512(const double* p, std::size_t lane,
                                                               double value, double* m) {
  __m512d v = _mm512_load_pd(p);
  v = _mm512_mask_mov_pd(v, static_cast<__mmask8>(1U << lane), _mm512_set1_pd(value));
  // maskz extracts: GCC 12's plain extract/cast read an "undefined" vector and warn
  // (-Wmaybe-uninitialized); with an all-ones mask the result is the same.
  const __m256d h = _mm256_min_pd(_mm512_maskz_extractf64x4_pd(0xF, v, 0),
                                  _mm512_maskz_extractf64x4_pd(0xF, v, 1));
  __m128d q = _mm_min_pd(_mm256_castpd256_pd128(h), _mm256_extractf128_pd(h, 1));
  q = _mm_min_sd(q, _mm_unpackhi_pd(q, q));
  const double mm = _mm_cvtsd_f64(q);
  const __mmask8 eq = _mm512_cmp_pd_mask(v, _mm512_set1_pd(mm), _CMP_EQ_OQ);
  *m = mm;
  return static_cast<unsigned>(__builtin_ctz(static_cast<unsigned>(eq)));
}

const bool kHasAvx512 = [] {
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx512f") != 0;
}();
}  // namespace

__attribute__((target("avx512f"))) void EventTree::update_top_avx512(double time) {
  update_top_with<argmin_line_avx512>(time);
}

__attribute__((target("avx512f"))) std::uint32_t EventTree::runner_up_avx512() {
  return runner_up_with<argmin_line_avx512>();
}

std::uint32_t EventTree::runner_up() {
  return kHasAvx512 ? runner_up_avx512() : runner_up_with<argmin_line_with>();
}

void EventTree::update_top(double time) {
  if (kHasAvx512) {
    update_top_avx512(time);
  } else {
    update_top_with<argmin_line_with>(time);
  }
}
#else
void EventTree::update_top_avx512(double time) {
  update_top_with<argmin_line_with>(time);
}
void EventTree::update_top(double time) {
  update_top_with<argmin_line_with>(time);
}
std::uint32_t EventTree::runner_up_avx512() {
  return runner_up_with<argmin_line_with>();
}
std::uint32_t EventTree::runner_up() {
  return runner_up_with<argmin_line_with>();
}
#endif

void EventTree::update_top_portable(double time) {
  update_top_with<argmin_line_with>(time);
}

std::uint32_t EventTree::runner_up_portable() {
  return runner_up_with<argmin_line_with>();
}

bool EventTree::valid() const {
  if (n_ == 0) return min_.empty();
  EventTree fresh;
  fresh.assign(times());
  return fresh.depth_ == depth_ && fresh.arg_ == arg_ &&
         std::equal(min_.begin(), min_.end(), fresh.min_.begin(), fresh.min_.end());
}

}  // namespace sadr::ssa
