// SPDX-License-Identifier: MIT
/// \file output_settings.hpp
/// What a run writes and when (the scene's `output` section): frame times and formats, the
/// species written, checkpoints, the VTK array encoding and the named observables.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace sadr::orchestrator {

/// How .vtu/.vtp frames store their arrays: raw binary appended data (as ParaView
/// writes by default: compact and fast) or ASCII text (readable by eye and by scripts).
enum class VtkEncoding { kBinary, kAscii };

enum class OutputFormat { kVtu, kVtp, kCsv };
std::string_view to_string(OutputFormat format);

/// A scalar the scene names for the sweep's observables.csv (output.observables):
/// per frame, the sum (`mean` false) or the mean over the particles of `region`
/// (at that frame's positions) of the species column `species`.
struct ObservableSpec {
  std::string name;
  std::string species;
  std::string region = "all";
  bool mean = false;
};

struct OutputSettings {
  std::string directory;      ///< "" = chosen by the CLI
  std::vector<double> times;  ///< sorted, unique, in [0, end], always ends with `end` [time]
  std::vector<OutputFormat> formats{OutputFormat::kVtu, OutputFormat::kCsv};
  std::vector<std::string> species;  ///< species written per frame (default all)
  double checkpoint_every = 0.0;     ///< simulated time between checkpoints; 0 = only on signal
  VtkEncoding vtk_encoding = VtkEncoding::kBinary;  ///< .vtu/.vtp array storage
  std::vector<ObservableSpec> observables;          ///< named scalars (sweeps)
};

}  // namespace sadr::orchestrator
