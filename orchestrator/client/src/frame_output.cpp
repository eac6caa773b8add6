// SPDX-License-Identifier: MIT
#include "sadr/orchestrator/frame_output.hpp"

#include <algorithm>
#include <cstdio>
#include <map>
#include <string>

#include "sadr/orchestrator/atomic_file.hpp"

namespace sadr::orchestrator {
namespace {

std::string frame_name(std::size_t index, const char* ext) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "frames/frame_%06zu.%s", index, ext);
  return buf;
}

}  // namespace

FrameOutput::FrameOutput(const Scene& scene, const std::filesystem::path& output_dir,
                         RunManifest& manifest)
    : scene_(scene),
      dir_(output_dir),
      manifest_(manifest),
      pvd_(output_dir / (scene.name.empty() ? "frames.pvd" : scene.name + ".pvd")) {
  ensure_directory(output_dir / "frames");
}

std::vector<SpeciesColumn> FrameOutput::write(std::size_t index, double t, FluidService* fluid,
                                              SsaService* ssa, const ParticleState& particles) {
  ParticleState state = particles;
  std::map<std::string, std::vector<double>> values;
  if (fluid) {
    std::vector<std::string> deterministic;
    for (const auto& name : scene_.output.species) {
      const Species* s = scene_.find_species(name);
      if (s && !s->stochastic) deterministic.push_back(name);
    }
    FluidFrame f = fluid->frame(deterministic);
    state = std::move(f.particles);
    for (auto& [name, c] : f.concentrations) values[name] = std::move(c);
  }
  if (ssa) {
    std::vector<std::string> stochastic;
    for (const auto& name : scene_.output.species) {
      const Species* s = scene_.find_species(name);
      if (s && s->stochastic) stochastic.push_back(name);
    }
    if (!stochastic.empty()) {
      const SpeciesCounts counts = ssa->counts(stochastic);
      for (std::size_t k = 0; k < counts.names.size(); ++k) {
        auto& v = values[counts.names[k]];
        v.assign(counts.values[k].begin(), counts.values[k].end());
      }
    }
  }
  std::vector<SpeciesColumn> columns;
  for (const auto& name : scene_.output.species) {
    auto it = values.find(name);
    if (it != values.end()) columns.push_back(SpeciesColumn{name, std::move(it->second)});
  }
  if (state.velocities.empty()) state.velocities.assign(3 * state.size(), 0.0);
  for (OutputFormat f : scene_.output.formats) {
    switch (f) {
      case OutputFormat::kVtu:
        write_vtu(dir_ / frame_name(index, "vtu"), t, state, columns, scene_.output.vtk_encoding);
        break;
      case OutputFormat::kVtp:
        write_vtp(dir_ / frame_name(index, "vtp"), t, state, columns, scene_.output.vtk_encoding);
        break;
      case OutputFormat::kCsv:
        write_frame_csv(dir_ / frame_name(index, "csv"), t, state, columns);
        break;
    }
  }
  list(index, t);
  return columns;
}

void FrameOutput::relist_until(double t) {
  for (std::size_t k = 0; k < scene_.output.times.size(); ++k) {
    if (scene_.output.times[k] > t) break;
    list(k, scene_.output.times[k]);
  }
}

void FrameOutput::list(std::size_t index, double t) {
  const auto& formats = scene_.output.formats;
  auto has = [&](OutputFormat f) {
    return std::find(formats.begin(), formats.end(), f) != formats.end();
  };
  if (has(OutputFormat::kVtu)) {
    pvd_.add(t, dir_ / frame_name(index, "vtu"));
  } else if (has(OutputFormat::kVtp)) {
    pvd_.add(t, dir_ / frame_name(index, "vtp"));
  }
  for (OutputFormat f : formats) {
    const char* ext = f == OutputFormat::kVtu ? "vtu" : f == OutputFormat::kVtp ? "vtp" : "csv";
    manifest_.frames.push_back(frame_name(index, ext));
  }
}

}  // namespace sadr::orchestrator
