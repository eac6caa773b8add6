// SPDX-License-Identifier: MIT
// `sadr ensemble DIR`: per-frame ensemble mean and variance from the CSV
// frames of realizations run separately (e.g. one Slurm array task each).
// The result equals what `sadr run -r R` writes for the same realizations.
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "sadr/orchestrator/atomic_file.hpp"
#include "sadr/orchestrator/ensemble_accumulator.hpp"
#include "sadr/orchestrator/hash.hpp"
#include "sadr/orchestrator/run_manifest.hpp"
#include "sadr/orchestrator/scene_loader.hpp"
#include "sadr/orchestrator/sweep_frames.hpp"

namespace sadr::orchestrator {
namespace fs = std::filesystem;

void write_ensemble_manifest(const fs::path& dir, const Scene& scene, int realizations, int retries,
                             const std::vector<FailedRealization>& failed) {
  nlohmann::json f = nlohmann::json::array();
  for (const auto& x : failed) {
    f.push_back({{"realization", x.realization},
                 {"exit_code", x.exit_code},
                 {"reason", x.reason},
                 {"attempts", x.attempts}});
  }
  const nlohmann::json j{{"format", "sadr-ensemble"},
                         {"format_version", 1},
                         {"scene_path", fs::absolute(scene.source_path).string()},
                         {"overrides", scene.overrides},
                         {"scene_hash", scene.source_hash},
                         {"realizations", realizations},
                         {"retries", retries},
                         {"failed", f}};
  write_file_atomic(dir / "ensemble.json", j.dump(2) + "\n");
}

int report_failed_realizations(const fs::path& dir, const std::vector<FailedRealization>& failed) {
  std::fprintf(stderr,
               "sadr: %zu realizations failed (the ensemble/ files count the others in "
               "their realizations column):\n  %-11s %-8s %-4s %s\n",
               failed.size(), "realization", "attempts", "exit", "reason");
  for (const auto& f : failed) {
    std::fprintf(stderr, "  %-11d %-8d %-4d %s\n", f.realization, f.attempts, f.exit_code,
                 f.reason.substr(0, f.reason.find('\n')).c_str());
  }
  std::fprintf(stderr, "sadr: run or resume them with: sadr resume %s\n", dir.string().c_str());
  return kExitServiceFailure;
}

std::optional<FailedRealization> run_ensemble_member(const Scene& scene, const Plan& plan,
                                                     const CliOptions& o, int r, const fs::path& rd,
                                                     bool from_checkpoint, const RunOptions& base,
                                                     const std::function<void()>& before_attempt,
                                                     RunResult& result) {
  const fs::path cp = rd / "checkpoint" / std::string(kCheckpointManifestName);
  for (int attempt = 1;; ++attempt) {
    if (before_attempt) before_attempt();
    try {
      std::optional<LoadedCheckpoint> resume;
      if (from_checkpoint && fs::exists(cp)) {
        resume = load_checkpoint(cp, scene.source_hash);
      } else if (attempt > 1) {  // from t = 0: nothing of the failed attempt stays
        for (const auto* sub : {"frames", "checkpoint"}) fs::remove_all(rd / sub);
      }
      result = run_realization(scene, plan, o, static_cast<std::uint64_t>(r), rd,
                               resume ? &*resume : nullptr, base);
      return std::nullopt;
    } catch (const std::exception& e) {
      FailedRealization f{r, exit_code_of(e), e.what(), attempt};
      if (attempt > o.retries || interrupt_requested()) return f;
      std::fprintf(
          stderr, "sadr: realization %d, attempt %d of %d failed (exit %d): %s; retrying%s\n", r,
          attempt, o.retries + 1, f.exit_code, f.reason.substr(0, f.reason.find('\n')).c_str(),
          from_checkpoint && fs::exists(cp) ? " from its last checkpoint" : " from t = 0");
    }
  }
}

int resume_ensemble(const CliOptions& o, const fs::path& dir) {
  const nlohmann::json j = nlohmann::json::parse(read_file_bytes(dir / "ensemble.json"));
  const auto overrides = parse_overrides(j.at("overrides").get<std::vector<std::string>>());
  const Scene scene = load_scene(j.at("scene_path").get<std::string>(), overrides);
  if (scene.source_hash != j.at("scene_hash").get<std::string>()) {
    throw InvalidArgument((dir / "ensemble.json").string() + ": the scene " +
                          j.at("scene_path").get<std::string>() +
                          " changed since the ensemble started (hash " + scene.source_hash +
                          ", was " + j.at("scene_hash").get<std::string>() + ")");
  }
  Plan plan = make_plan(scene);
  const int count = j.at("realizations").get<int>();
  std::vector<FailedRealization> failed;
  int executed = 0;
  for (int r = 0; r < count && !interrupt_requested(); ++r) {
    const fs::path rd = dir / realization_dir_name(static_cast<std::uint64_t>(r));
    if (fs::exists(rd / "run.json") &&
        nlohmann::json::parse(read_file_bytes(rd / "run.json")).value("status", "") == "ok") {
      continue;
    }
    ++executed;
    const bool resumed = fs::exists(rd / "checkpoint" / std::string(kCheckpointManifestName));
    RunOptions base;
    base.progress = false;
    RunResult res;
    if (auto f = run_ensemble_member(scene, plan, o, r, rd, true, base, {}, res)) {
      std::fprintf(stderr, "sadr: realization %d failed: %s\n", r, f->reason.c_str());
      failed.push_back(std::move(*f));
    } else {
      std::fprintf(stderr, "sadr: realization %d %s\n", r,
                   res.interrupted ? "interrupted"
                   : resumed       ? "resumed and done"
                                   : "done");
    }
  }
  write_ensemble_manifest(dir, scene, count, o.retries, failed);
  std::fprintf(stderr, "sadr: resumed %d of %d realizations\n", executed, count);
  if (!failed.empty()) return report_failed_realizations(dir, failed);
  if (interrupt_requested()) return kExitInterrupted;
  CliOptions combine = o;
  combine.directory = dir.string();
  return cmd_ensemble(combine);
}

int cmd_ensemble(const CliOptions& o) {
  const fs::path dir = o.directory;
  std::vector<fs::path> realizations;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.is_directory() && is_realization_dir_name(e.path().filename().string())) {
      realizations.push_back(e.path());
    }
  }
  std::sort(realizations.begin(), realizations.end());
  if (realizations.empty()) {
    throw InvalidArgument("'" + dir.string() + "' holds no realization_NNNN/ folders");
  }
  std::optional<EnsembleAccumulator> acc;
  std::vector<std::uint64_t> ids;
  std::map<std::size_t, fs::path> expected;  // the first realization's frames
  std::size_t used = 0;
  std::string hash, hash_of;  // the effective scene of the first realization with a run.json
  for (const auto& r : realizations) {
    // Never mix runs of different effective scenes (an edited scene, other --set values).
    if (fs::exists(r / "run.json")) {
      std::string h;
      try {
        h = nlohmann::json::parse(read_file_bytes(r / "run.json")).value("scene_hash", "");
      } catch (const nlohmann::json::exception& e) {
        throw InvalidArgument((r / "run.json").string() + ": not valid JSON: " + e.what());
      }
      if (hash.empty()) {
        hash = h;
        hash_of = r.string();
      } else if (!h.empty() && h != hash) {
        throw InvalidArgument(r.string() + " ran the effective scene " + h + ", " + hash_of +
                              " ran " + hash +
                              "; refusing to combine runs of different scenes (or --set values)");
      }
    }
    const auto frames = list_csv_frames(r);
    if (frames.empty()) {
      std::fprintf(stderr, "sadr: %s has no CSV frames (add csv to output.formats); skipped\n",
                   r.string().c_str());
      continue;
    }
    if (used == 0) expected = frames;
    // Every realization must have the same frames: never average a frame
    // over fewer realizations than the others without a word.
    for (const auto& [k, p] : expected) {
      if (!frames.count(k)) {
        throw InvalidArgument(r.string() + ": frame " + p.filename().string() + " is missing (" +
                              expected.at(k).parent_path().parent_path().string() +
                              " has it); every realization needs the same frames");
      }
    }
    for (const auto& [k, p] : frames) {
      if (!expected.count(k)) {
        throw InvalidArgument(p.string() + ": not among the frames of the first realization");
      }
    }
    for (const auto& [index, path] : frames) {
      const CsvFrame f = read_frame_csv(path);  // file:row: column: value on a bad cell
      if (!acc) {
        std::vector<std::string> names;
        for (const auto& s : f.species) names.push_back(s.name);
        acc.emplace(names, f.particles.ids.size());
        ids = f.particles.ids;
      }
      try {
        acc->add(index, f.time, f.species);
      } catch (const Error& e) {
        throw InvalidArgument(path.string() + ": " + e.what());
      }
    }
    ++used;
  }
  if (!acc) throw InvalidArgument("no CSV frames found under '" + dir.string() + "'");
  ensure_directory(dir / "ensemble");
  for (std::size_t k = 0; k < acc->frame_count(); ++k) {
    if (acc->realizations(k) == 0) continue;
    char name[48];
    std::snprintf(name, sizeof name, "ensemble/frame_%06zu.csv", k);
    acc->write_csv(k, dir / name, ids);
  }
  std::fprintf(stderr, "sadr: combined %zu realizations into %s\n", used,
               (dir / "ensemble").string().c_str());
  return kExitOk;
}

}  // namespace sadr::orchestrator
