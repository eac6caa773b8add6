// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/restart_policy.hpp"

#include <cstdio>
#include <exception>

#include "sadr/common/log.hpp"
#include "sadr/orchestrator/exit_codes.hpp"

namespace sadr::orchestrator {
namespace fs = std::filesystem;

bool is_service_failure(const Error& e) {
  return e.code() == StatusCode::kUnavailable || e.code() == StatusCode::kDeadlineExceeded;
}

bool should_restart(const RestartPolicy& policy, const Error& e, int attempt) {
  return is_service_failure(e) && attempt < policy.restarts && !policy.remote;
}

std::optional<LoadedCheckpoint> restart_point(const RestartPolicy& policy, const Error& e,
                                              int attempt, std::uint64_t realization,
                                              const fs::path& out, const std::string& scene_hash) {
  const fs::path cp = out / "checkpoint" / std::string(kCheckpointManifestName);
  log::warn("realization ", realization, ": ", e.what(), "; restarting the services (", attempt + 1,
            " of ", policy.restarts, ")",
            fs::exists(cp) ? " from the last checkpoint" : " from t = 0 (no checkpoint yet)");
  if (fs::exists(cp)) return load_checkpoint(cp, scene_hash);
  return std::nullopt;
}

std::optional<FailedRealization> run_with_retries(
    const RetryPolicy& policy, int r, const fs::path& rd, const std::string& scene_hash,
    const std::function<void()>& before_attempt,
    const std::function<void(const LoadedCheckpoint*)>& attempt,
    const std::function<bool()>& interrupted) {
  const fs::path cp = rd / "checkpoint" / std::string(kCheckpointManifestName);
  for (int n = 1;; ++n) {
    if (before_attempt) before_attempt();
    try {
      std::optional<LoadedCheckpoint> resume;
      if (policy.from_checkpoint && fs::exists(cp)) {
        resume = load_checkpoint(cp, scene_hash);
      } else if (n > 1) {  // from t = 0: nothing of the failed attempt stays
        for (const auto* sub : {"frames", "checkpoint"}) fs::remove_all(rd / sub);
      }
      attempt(resume ? &*resume : nullptr);
      return std::nullopt;
    } catch (const std::exception& e) {
      FailedRealization f{r, exit_code_of(e), e.what(), n};
      if (n > policy.retries || (interrupted && interrupted())) return f;
      std::fprintf(
          stderr, "sadr: realization %d, attempt %d of %d failed (exit %d): %s; retrying%s\n", r, n,
          policy.retries + 1, f.exit_code, f.reason.substr(0, f.reason.find('\n')).c_str(),
          policy.from_checkpoint && fs::exists(cp) ? " from its last checkpoint" : " from t = 0");
    }
  }
}

}  // namespace sadr::orchestrator
