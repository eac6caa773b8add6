// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/ensemble_pool.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <mutex>
#include <thread>

#include "sadr/orchestrator/atomic_file.hpp"
#include "sadr/orchestrator/reorder_buffer.hpp"

namespace sadr::orchestrator {

PoolResult run_ensemble_pool(EnsembleAccumulator& ensemble, int count, int jobs, bool quiet,
                             const std::atomic<bool>& interrupt,
                             const std::function<MemberResult(int)>& member) {
  PoolResult result;
  ReorderBuffer<RealizationFrames> buffer([&ensemble](int, RealizationFrames& frames) {
    for (const auto& [k, f] : frames) ensemble.add(k, f.first, f.second);
  });
  std::mutex mutex;
  std::atomic<int> next{0}, done{0};
  const auto t0 = std::chrono::steady_clock::now();
  auto worker = [&] {
    for (int r; (r = next++) < count && !interrupt;) {
      MemberResult res = member(r);
      std::lock_guard lock(mutex);
      if (res.failure) {
        // Recorded; the other realizations go on (docs/sweeps.md: faults).
        std::fprintf(stderr, "sadr: realization %d failed: %s\n", r, res.failure->reason.c_str());
        result.failed.push_back(std::move(*res.failure));
        buffer.complete(r, {});  // adds nothing; the later ones are added in order
        continue;
      }
      // An interrupted realization is never completed: neither it nor any later one is added
      // (the ensemble files then hold the realizations before it).
      if (!res.interrupted) buffer.complete(r, std::move(res.frames));
      const int d = ++done;
      const double el =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (!quiet) {
        std::fprintf(stderr, "sadr: realization %d done (%d/%d), elapsed %.1f s, ETA %.1f s\n", r,
                     d, count, el, el / d * (count - d));
      }
    }
  };
  std::vector<std::thread> pool;
  for (int j = 0; j < jobs; ++j) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  std::sort(result.failed.begin(), result.failed.end(),
            [](const auto& x, const auto& y) { return x.realization < y.realization; });
  result.done = done.load();
  return result;
}

void write_ensemble_frames(const EnsembleAccumulator& ensemble, const std::filesystem::path& dir,
                           std::span<const std::uint64_t> ids) {
  ensure_directory(dir / "ensemble");
  for (std::size_t k = 0; k < ensemble.frame_count(); ++k) {
    if (ensemble.realizations(k) == 0) continue;
    char name[48];
    std::snprintf(name, sizeof name, "ensemble/frame_%06zu.csv", k);
    ensemble.write_csv(k, dir / name, ids);
  }
}

}  // namespace sadr::orchestrator
