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

/// The assigned species written (scene.output.species), each with its law.
std::vector<std::pair<std::string, rate_law::RateLaw>> assigned_laws(const Scene& scene) {
  std::vector<std::pair<std::string, rate_law::RateLaw>> out;
  std::vector<std::string> names;
  for (const auto& sp : scene.species) names.push_back(sp.name);
  for (const auto& name : scene.output.species) {
    const AssignedSpecies* a = scene.find_assigned(name);
    if (!a) continue;
    rate_law::Definition d;
    d.type = rate_law::Type::kExpression;
    d.expression = a->expanded;
    d.parameters = scene.parameters;
    d.origin = a->origin;
    out.emplace_back(name, rate_law::RateLaw(d, names, false));
  }
  return out;
}

/// The stochastic (or deterministic) species a frame reads: the output species,
/// then those the assigned ones read (`inputs`) and are not written.
std::vector<std::string> frame_species(const Scene& scene, const std::set<std::string>& inputs,
                                       bool stochastic) {
  std::vector<std::string> out;
  for (const auto& name : scene.output.species) {
    const Species* s = scene.find_species(name);
    if (s && s->stochastic == stochastic) out.push_back(name);
  }
  for (const auto& name : inputs) {
    const Species* s = scene.find_species(name);
    if (s->stochastic == stochastic && std::find(out.begin(), out.end(), name) == out.end()) {
      out.push_back(name);
    }
  }
  return out;
}

}  // namespace

FrameOutput::FrameOutput(const Scene& scene, const std::filesystem::path& output_dir,
                         RunManifest& manifest)
    : scene_(scene),
      dir_(output_dir),
      manifest_(manifest),
      pvd_(output_dir / (scene.name.empty() ? "frames.pvd" : scene.name + ".pvd")),
      assigned_(assigned_laws(scene)) {
  ensure_directory(output_dir / "frames");
  std::set<std::string> inputs;  // species the assigned ones read
  for (const auto& [name, law] : assigned_) {
    for (const int s : law.species()) inputs.insert(scene.species[s].name);
  }
  fluid_species_ = frame_species(scene, inputs, false);
  ssa_species_ = frame_species(scene, inputs, true);
}

std::vector<std::string> frame_fluid_species(const Scene& scene) {
  std::set<std::string> inputs;
  for (const auto& [name, law] : assigned_laws(scene)) {
    for (const int s : law.species()) inputs.insert(scene.species[s].name);
  }
  return frame_species(scene, inputs, false);
}

void FrameOutput::evaluate_assigned(std::map<std::string, std::vector<double>>& values,
                                    const ParticleState& state) {
  const std::size_t n = state.size();
  for (auto& [name, law] : assigned_) {
    const std::vector<int>& sp = law.species();
    std::vector<const std::vector<double>*> in;
    std::vector<bool> counts;
    for (const int s : sp) {
      const Species& species = scene_.species[s];
      in.push_back(&values.at(species.name));
      counts.push_back(species.stochastic);
    }
    std::vector<double> c(sp.size()), out(n);
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t k = 0; k < sp.size(); ++k) {
        c[k] = (*in[k])[i] / (counts[k] ? state.volume(i) : 1.0);
      }
      out[i] = law.density(c.data(), 0.0);
    }
    values[name] = std::move(out);
  }
}

std::vector<SpeciesColumn> FrameOutput::write(std::size_t index, double t, FluidService* fluid,
                                              SsaService* ssa, const ParticleState& particles) {
  ParticleState state = particles;
  std::map<std::string, std::vector<double>> values;
  if (fluid) {
    FluidFrame f = fluid->frame(fluid_species_);
    state = std::move(f.particles);
    for (auto& [name, c] : f.concentrations) values[name] = std::move(c);
  }
  if (ssa && !ssa_species_.empty()) {
    const SpeciesCounts counts = ssa->counts(ssa_species_);
    for (std::size_t k = 0; k < counts.names.size(); ++k) {
      auto& v = values[counts.names[k]];
      v.assign(counts.values[k].begin(), counts.values[k].end());
    }
  }
  if (!assigned_.empty()) evaluate_assigned(values, state);
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
