// SPDX-License-Identifier: MIT
/// \file sweep_frames.hpp
/// Reads back the CSV frames that a run writes (frame_writers.hpp), strictly:
/// every cell must be a finite number, every row must have the header's
/// columns, and a problem is reported with file, row, column and value.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <vector>

#include "sadr/common/particle_state.hpp"
#include "sadr/orchestrator/frame_writers.hpp"

namespace sadr::orchestrator {

/// One CSV frame: time, the particles (positions, velocities, density, mass,
/// kind, id) and the species columns.
struct CsvFrame {
  double time = 0;
  ParticleState particles;  ///< dimension 3 (unused axes are 0 in the file)
  std::vector<SpeciesColumn> species;
};

/// @throws sadr::InvalidArgument "file:row: column 'A': 'abc' is not a finite number".
CsvFrame read_frame_csv(const std::filesystem::path& path);

/// The CSV frames of a run directory (`dir`/frames/frame_NNNNNN.csv) by output index.
std::map<std::size_t, std::filesystem::path> list_csv_frames(const std::filesystem::path& dir);

}  // namespace sadr::orchestrator
