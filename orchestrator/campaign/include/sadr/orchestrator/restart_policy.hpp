// SPDX-License-Identifier: MIT
/// \file restart_policy.hpp
/// When a realization is run again, and from where:
/// - restarts (--restart-on-failure N): a service died or stopped answering;
///   the services are relaunched, from the last checkpoint if there is one;
/// - retries (--retries N, ensembles): a realization failed for any reason;
///   it runs again from its last checkpoint or from t = 0.
/// The realization itself is a function the caller passes in.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "sadr/common/status.hpp"
#include "sadr/orchestrator/checkpoint.hpp"
#include "sadr/orchestrator/ensemble_manifest.hpp"

namespace sadr::orchestrator {

/// --restart-on-failure: up to `restarts` relaunches of the services after a
/// service failure (unavailable, deadline exceeded); never for remote services.
struct RestartPolicy {
  int restarts = 0;
  bool remote = false;  ///< services not launched here cannot be relaunched
};

/// A service that died or did not answer (what a restart can cure).
[[nodiscard]] bool is_service_failure(const Error& e);
/// Whether attempt `attempt` (0-based) that failed with `e` is followed by another.
[[nodiscard]] bool should_restart(const RestartPolicy& policy, const Error& e, int attempt);
/// Logs the restart of realization `realization` into `out` and loads the
/// checkpoint it restarts from (nothing when `out` holds none yet).
std::optional<LoadedCheckpoint> restart_point(const RestartPolicy& policy, const Error& e,
                                              int attempt, std::uint64_t realization,
                                              const std::filesystem::path& out,
                                              const std::string& scene_hash);

/// Runs `run(session, resume)` with a fresh `start()` session (the services)
/// per attempt until it returns, relaunching per `policy`. A failure of
/// start() itself is not restarted. The first attempt resumes from `resume`;
/// a restart from the last checkpoint under `out`, else again from `resume`.
template <class Start, class Run>
auto run_with_restarts(const RestartPolicy& policy, std::uint64_t realization,
                       const std::filesystem::path& out, const std::string& scene_hash,
                       const LoadedCheckpoint* resume, Start&& start, Run&& run) {
  std::optional<LoadedCheckpoint> reloaded;
  for (int attempt = 0;; ++attempt) {
    auto session = start();
    try {
      return run(session, reloaded ? &*reloaded : resume);
    } catch (const Error& e) {
      if (!should_restart(policy, e, attempt)) throw;
      reloaded = restart_point(policy, e, attempt, realization, out, scene_hash);
    }
  }
}

/// --retries: a failed realization of an ensemble runs up to `retries` more times.
struct RetryPolicy {
  int retries = 1;
  /// Each retry resumes from the realization's last checkpoint (if any); else it
  /// starts at t = 0 with the failed attempt's frames and checkpoints removed.
  bool from_checkpoint = false;
};

/// Realization `r` in `rd`: `attempt(resume)` until it returns or the retries
/// are spent (or `interrupted()`). `before_attempt` runs before every attempt.
/// Returns the last failure, or nothing when an attempt returned.
std::optional<FailedRealization> run_with_retries(
    const RetryPolicy& policy, int r, const std::filesystem::path& rd,
    const std::string& scene_hash, const std::function<void()>& before_attempt,
    const std::function<void(const LoadedCheckpoint*)>& attempt,
    const std::function<bool()>& interrupted);

}  // namespace sadr::orchestrator
