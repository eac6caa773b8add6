// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/run_summary.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sadr/common/status.hpp"
#include "sadr/orchestrator/run_health.hpp"
#include "sadr/orchestrator/run_manifest.hpp"
#include "sadr/orchestrator/scene_loader.hpp"
#include "sadr/orchestrator/scene_override.hpp"
#include "sadr/orchestrator/summary_totals.hpp"
#include "sadr/orchestrator/sweep_frames.hpp"

namespace sadr::orchestrator {
namespace fs = std::filesystem;
namespace {

/// Totals of each species at the first and last frame; a deterministic
/// species (plan.fluid_species: a concentration) as its amount sum c_i V_i.
void print_species(std::FILE* out, const std::vector<fs::path>& csv, bool ensemble,
                   const nlohmann::json& plan) {
  if (csv.empty()) {
    std::fprintf(out, "  species totals: no CSV frames (add csv to output.formats)\n");
    return;
  }
  const ColumnTotals a = sum_columns(csv.front(), ensemble);
  const ColumnTotals b = sum_columns(csv.back(), ensemble);
  char first[48], last[48];
  std::snprintf(first, sizeof first, "first frame, t = %g", a.time);
  std::snprintf(last, sizeof last, "last frame, t = %g", b.time);
  std::fprintf(out, "  species totals%s:\n    %-32s %22s  %22s\n",
               ensemble ? " of the ensemble mean" : "", "", first, last);
  const auto& fluid =
      plan.contains("fluid_species") ? plan["fluid_species"] : nlohmann::json::array();
  for (std::size_t k = 0; k < a.names.size() && k < b.names.size(); ++k) {
    const bool concentration = std::find(fluid.begin(), fluid.end(), a.names[k]) != fluid.end();
    std::string label = a.names[k];
    if (concentration) label += ensemble ? " (sum of concentrations)" : " (amount, sum c V)";
    const bool amount = concentration && !ensemble;
    std::fprintf(out, "    %-32s %22.10g  %22.10g\n", label.c_str(),
                 amount ? a.amounts[k] : a.totals[k], amount ? b.amounts[k] : b.totals[k]);
  }
}

void print_stages(std::FILE* out, const ManifestTotals& t) {
  const auto get = [&](const char* k) {
    const auto it = t.timings.find(k);
    return it == t.timings.end() ? 0.0 : it->second;
  };
  std::fprintf(out, "  wall time per stage [s]:\n");
  const struct {
    const char* label;
    double seconds;
    const char* note;
  } rows[] = {
      {"fluid", get("fluid"), "fluid_service calls (its own compute time below)"},
      {"  fluid compute", get("fluid_compute"), "inside fluid_service"},
      {"transfer", get("transfer") + get("back_transfer"), "particles to ssa, counts back"},
      {"graph rebuild", get("ssa_graph"), "inside ssa_service"},
      {"NSM", get("ssa_nsm"), "inside ssa_service"},
      {"ssa (call)", get("ssa"), "ssa_service calls, rebuild + NSM + messages"},
      {"ssa wait", get("ssa_wait"), "SSA time the overlapped fluid did not hide"},
      {"output", get("output"), "frames"},
      {"checkpoint", get("checkpoint"), ""},
      {"coupling loop", get("coupling_loop"), "all of the above, wall clock"},
  };
  for (const auto& r : rows) {
    std::fprintf(out, "    %-16s %10.3f   %s\n", r.label, r.seconds, r.note);
  }
}

/// The health section (run_health.hpp): the run's scene read again (scene_path and overrides of
/// run.json, same hash), else values estimated from the first frame; at most 64 CSV frames in all,
/// evenly spaced over each run's frames, the first and last of each always.
void print_health(std::FILE* out, const std::vector<fs::path>& runs, const nlohmann::json& first) {
  HealthContext context;
  std::string note;
  try {
    const Scene scene =
        load_scene(first.value("scene_path", ""),
                   parse_overrides(first.value("overrides", std::vector<std::string>{})));
    if (scene.source_hash == first.value("scene_hash", "")) {
      context = health_context(scene);
    } else {
      note = "the scene file changed since the run (hash " + scene.source_hash + ")";
    }
  } catch (const std::exception& e) {
    note = std::string("the scene could not be read again: ") + e.what();
  }
  if (!context.from_scene) {
    const nlohmann::json plan = first.value("plan", nlohmann::json::object());
    for (const auto& name : plan.value("fluid_species", std::vector<std::string>{})) {
      context.species.push_back({name, false, {}, {}});
    }
  }
  HealthCheck check(std::move(context));
  const std::size_t per_run = std::max<std::size_t>(2, 64 / std::max<std::size_t>(1, runs.size()));
  for (std::size_t r = 0; r < runs.size(); ++r) {
    std::vector<fs::path> frames;
    for (const auto& [index, path] : list_csv_frames(runs[r])) frames.push_back(path);
    const std::size_t n = frames.size();
    const std::size_t take = std::min(n, per_run);
    for (std::size_t k = 0; k < take; ++k) {
      const std::size_t i = take == 1 ? n - 1 : k * (n - 1) / (take - 1);
      const CsvFrame f = read_frame_csv(frames[i]);
      check.add_frame(f.particles, f.species, f.time, frames[i].string(), r);
    }
  }
  if (check.frames() == 0) {
    std::fprintf(out, "  health: no CSV frames (add csv to output.formats)\n");
    return;
  }
  const auto lines = check.lines();
  for (std::size_t k = 0; k < lines.size(); ++k) {
    std::fprintf(out, "  %s\n", lines[k].c_str());
    if (k == 0 && !note.empty()) std::fprintf(out, "    (%s)\n", note.c_str());
  }
}

/// run.json's body_forces (scene fluid.body_forces): per body the mean force and torque over
/// the run's second half (else the last fluid stage's).
void print_body_forces(std::FILE* out, const nlohmann::json& run) {
  const auto it = run.find("body_forces");
  if (it == run.end() || !it->is_object() || it->empty()) return;
  std::fprintf(out, "  forces on bodies (body_forces.csv):\n");
  for (const auto& [name, b] : it->items()) {
    const bool mean = b.contains("mean_force");
    const auto f = b.value(mean ? "mean_force" : "force", std::vector<double>(3, 0.0));
    const auto tq = b.value(mean ? "mean_torque" : "torque", std::vector<double>(3, 0.0));
    if (f.size() != 3 || tq.size() != 3) continue;
    const std::string when = mean ? "mean over t = " + format_short(b.value("mean_from", 0.0)) +
                                        "-" + format_short(b.value("mean_to", 0.0))
                                  : "at t = " + format_short(b.value("time", 0.0));
    std::fprintf(out, "    %s: F = (%.6g, %.6g, %.6g), T = (%.6g, %.6g, %.6g) (%s)\n", name.c_str(),
                 f[0], f[1], f[2], tq[0], tq[1], tq[2], when.c_str());
  }
}

}  // namespace

void print_summary(const fs::path& dir, std::FILE* out) {
  const bool is_run = fs::exists(dir / "run.json");
  std::vector<fs::path> realizations;
  if (!is_run && fs::is_directory(dir)) {
    for (const auto& e : fs::directory_iterator(dir)) {
      if (e.is_directory() && fs::exists(e.path() / "run.json") &&
          is_realization_dir_name(e.path().filename().string())) {
        realizations.push_back(e.path());
      }
    }
    std::sort(realizations.begin(), realizations.end());
  }
  if (!is_run && realizations.empty()) {
    throw InvalidArgument("'" + dir.string() +
                          "' is neither a run (run.json) nor an ensemble (realization_NNNN/)");
  }
  ManifestTotals t;
  nlohmann::json first;
  for (const auto& m : is_run ? std::vector<fs::path>{dir} : realizations) {
    const nlohmann::json j = read_run_json(m / "run.json");
    if (first.is_null()) first = j;
    t.add(j);
  }
  const std::size_t n = is_run ? 1 : realizations.size();
  std::fprintf(out, "sadr summary: %s\n", dir.string().c_str());
  std::fprintf(out, "  scene: %s (%s)\n", first.value("scene_path", "?").c_str(),
               first.value("scene_hash", "?").c_str());
  if (is_run) {
    std::fprintf(out, "  run: realization %llu, seed %llu, status %s, %s\n",
                 first.value("realization", 0ULL), first.value("seed", 0ULL),
                 t.statuses.front().c_str(), first.value("mode", "?").c_str());
  } else {
    const auto ok = std::count(t.statuses.begin(), t.statuses.end(), "ok");
    std::fprintf(out,
                 "  ensemble: %zu realizations (%td with status ok); counters and times summed\n",
                 n, ok);
  }
  std::fprintf(
      out, "  t = %g: %.0f coupling steps, %.0f fluid sub-steps (%.2f per step), %.0f overlapped\n",
      t.time, t.steps, t.substeps, t.steps > 0 ? t.substeps / t.steps : 0.0, t.overlapped);
  if (const auto sc = first.value("step_control", nlohmann::json::object());
      is_run && !sc.empty()) {
    std::fprintf(out,
                 "  error-controlled step (time.tolerance): %llu accepted, %llu rejected; step "
                 "%g to %g; largest estimated error %.3g of the tolerance\n",
                 sc.value("accepted", 0ULL), sc.value("rejected", 0ULL),
                 sc.value("smallest_step", 0.0), sc.value("largest_step", 0.0),
                 sc.value("largest_error", 0.0));
  }
  if (t.events_recorded) {
    std::fprintf(out, "  SSA events: %.0f (reactions + diffusion jumps)\n", t.events);
  } else {
    std::fprintf(out, "  SSA events: not in run.json (written before sadr recorded them)\n");
  }
  print_species(out, sorted_files(dir / (is_run ? "frames" : "ensemble"), ".csv"), !is_run,
                first.value("plan", nlohmann::json::object()));
  print_stages(out, t);
  print_health(out, is_run ? std::vector<fs::path>{dir} : realizations, first);
  if (is_run) print_body_forces(out, first);
  const fs::path run0 = is_run ? dir : realizations.front();
  const auto pvd = sorted_files(run0, ".pvd");
  const std::size_t frames = first.contains("frames") ? first["frames"].size() : 0;
  std::fprintf(out, "  outputs: %s/run.json, %s/frames/ (%zu files)%s%s%s%s\n",
               run0.string().c_str(), run0.string().c_str(), frames,
               pvd.empty() ? "" : ", ParaView: ", pvd.empty() ? "" : pvd.front().string().c_str(),
               fs::exists(run0 / "checkpoint") ? ", checkpoint/" : "",
               is_run ? "" : (", ensemble/ (mean, variance) in " + dir.string()).c_str());
}

}  // namespace sadr::orchestrator
