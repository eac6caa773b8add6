// SPDX-License-Identifier: MIT
/// \file frame_writers.hpp
/// Per-frame output written by hand (no VTK library): VTK XML UnstructuredGrid
/// (.vtu, one VTK_VERTEX cell per particle) or PolyData (.vtp, one vertex per
/// particle), and CSV. VTK arrays are raw binary appended data by default
/// (VtkEncoding::kBinary: the values' own bytes, native byte order declared in the
/// header, UInt64 block sizes) or ASCII; every ASCII number is the shortest decimal
/// that reads back as exactly the same double (std::to_chars). Either way a frame
/// reads back bit-identically. Files are written atomically (write_file_atomic): a
/// crash never leaves a half-written frame.
///
/// Point data in .vtu/.vtp: id (UInt64), kind (UInt8: 0 fluid, 1 wall,
/// 2 inlet, 3 outlet), velocity (Float64 x3), density, mass, one Float64 array
/// per species (copy numbers for stochastic species, concentrations for
/// deterministic ones). The frame time is the field-data array TimeValue (ASCII).
///
/// CSV columns: time,id,kind,x,y,z,vx,vy,vz,density,mass,<species...>
/// (kind as the integer code above; unused axes are 0).
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "sadr/common/particle_state.hpp"
#include "sadr/orchestrator/output_settings.hpp"

namespace sadr::orchestrator {

/// One named per-particle array (N values).
struct SpeciesColumn {
  std::string name;
  std::vector<double> values;
};

/// Writes a .vtu frame. @param time simulated time of the frame [time]
/// @throws sadr::InvalidArgument if a species column does not have N values.
void write_vtu(const std::filesystem::path& path, double time, const ParticleState& particles,
               std::span<const SpeciesColumn> species, VtkEncoding encoding = VtkEncoding::kBinary);

/// Writes a .vtp frame (PolyData with one vertex per particle).
void write_vtp(const std::filesystem::path& path, double time, const ParticleState& particles,
               std::span<const SpeciesColumn> species, VtkEncoding encoding = VtkEncoding::kBinary);

/// Writes a CSV frame (header row, then one row per particle).
void write_frame_csv(const std::filesystem::path& path, double time, const ParticleState& particles,
                     std::span<const SpeciesColumn> species);

/// Appends the shortest decimal that reads back as exactly `v` (std::to_chars; "inf" /
/// "nan" for non-finite values): round-trip exact like "%.17g", several times faster and
/// shorter (0.3, not 0.29999999999999999). The number format of every frame and ensemble file.
void append_number(std::string& out, double v);
/// Appends `v` in decimal.
void append_integer(std::string& out, std::uint64_t v);

/// The CSV header for these species: "time,id,kind,x,y,z,vx,vy,vz,density,mass,A,B".
std::string frame_csv_header(std::span<const SpeciesColumn> species);

/// A ParaView collection (.pvd) that is rewritten (atomically) after every
/// frame, so a crashed run still leaves a valid time series.
class PvdCollection {
 public:
  struct Entry {
    double time = 0.0;  ///< [time]
    std::string file;   ///< relative to the .pvd file's directory
  };

  explicit PvdCollection(std::filesystem::path path) : path_(std::move(path)) {}

  /// Adds a frame and rewrites the .pvd file.
  /// @param frame_file path of the frame; stored relative to the .pvd directory
  void add(double time, const std::filesystem::path& frame_file);
  [[nodiscard]] const std::vector<Entry>& entries() const { return entries_; }
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }
  /// The XML text of the collection.
  [[nodiscard]] std::string xml() const;

 private:
  std::filesystem::path path_;
  std::vector<Entry> entries_;
};

}  // namespace sadr::orchestrator
