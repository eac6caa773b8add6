// SPDX-License-Identifier: MIT
/// \file scene_geometry.hpp
/// Figures of a scene whose particles came from its `geometry` section (Scene::geometry), for
/// `sadr geometry`: the SPH number-density error of every particle against the ideal lattice's.
#pragma once

#include <vector>

#include "sadr/orchestrator/scene.hpp"

namespace sadr::orchestrator {

struct GeometryDensityError {
  /// Per particle: n_i / n_ref - 1 (Wendland C2 with support fluid.smoothing_length; walls and
  /// periodic images included; n_ref that of the ideal lattice).
  std::vector<double> per_particle;
  double max = 0.0;  ///< max |error| over the fluid particles
  double rms = 0.0;  ///< RMS over the fluid particles
};

/// The density error of the scene's particles as they are (after relaxation when the section
/// relaxes). Throws InvalidArgument when the scene has no geometry section.
GeometryDensityError geometry_density_error(const Scene& scene);

}  // namespace sadr::orchestrator
