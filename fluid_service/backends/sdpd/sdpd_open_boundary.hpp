// SPDX-License-Identifier: MIT
/// \file sdpd_open_boundary.hpp
/// The open channel of the SDPD backend (docs/fluid-core.md 2, "Open boundaries"): an inlet
/// conveyor upstream of the fluid and an outlet buffer downstream of it along a walled flow
/// axis. Buffer particles (kinds kInlet, kOutlet) feel no forces and no noise; after every
/// sub-step their kinds follow their position, outlet particles are recycled into the inlet,
/// the inlet gets its prescribed velocity and the outlet its pressure, and the values taken
/// from inside (inlet density, outlet velocity) are extrapolated from the fluid.
#pragma once

#include <cstdint>
#include <vector>

#include "sadr/common/particle_state.hpp"
#include "sadr/fluid/fluid_model.hpp"
#include "sadr/fluid/kernel.hpp"
#include "sadr/fluid/periodic_box.hpp"
#include "sadr/fluid/state_blob.hpp"

namespace sadr::fluid {

/// The particle arrays the open channel reads and changes.
struct OpenChannelFields {
  std::vector<double>& x;  ///< positions, 3N
  std::vector<double>& v;  ///< velocities, 3N
  std::vector<double>& rho;
  std::vector<ParticleKind>& kinds;
  const std::vector<double>& mass;
  const std::vector<std::uint8_t>& wall;  ///< 1: wall particle (never changes kind)
};

class OpenChannel {
 public:
  /// Off unless model.open_boundary.enabled; the initial inlet particles (non-wall, upstream of
  /// fluid_lo) become conveyor particles and take kind kInlet, the other non-wall ones kFluid.
  void setup(const FluidModel& model, const Kernel& kernel, const PeriodicBox& pbox,
             const std::vector<double>& x, const std::vector<std::uint8_t>& wall,
             std::vector<ParticleKind>& kinds);
  [[nodiscard]] bool enabled() const { return enabled_; }
  /// 1: particle i is an inlet or outlet particle (no forces, no noise, density set by apply).
  [[nodiscard]] bool buffer(std::size_t i) const { return buffer_[i] != 0; }
  /// After a sub-step of length dt (and at initialize with dt = 0).
  void apply(double dt, OpenChannelFields f);
  /// The saved part of the state (blob version 3): kinds, conveyor flags, inlet holes.
  void save(BlobWriter& w, const std::vector<ParticleKind>& kinds) const;
  /// Reads what save() wrote, checked against the wall flags; apply it with commit() once the
  /// whole blob has been read.
  struct Saved {
    std::vector<ParticleKind> kinds;
    std::vector<std::uint8_t> conveyor;
    std::vector<double> holes;
  };
  [[nodiscard]] static Saved read(BlobReader& r, const std::vector<std::uint8_t>& wall);
  void commit(Saved&& s, std::vector<ParticleKind>& kinds);
  /// Heap bytes held (benchmark diagnostics).
  [[nodiscard]] std::size_t bytes() const;

 private:
  /// Zero-gradient values of the `target` buffer particles (inlet: density; outlet: velocity)
  /// from the fluid particles with axis coordinate in [lo, hi).
  void extrapolate_from_fluid(ParticleKind target, double lo, double hi, OpenChannelFields& f);

  bool enabled_ = false;
  OpenBoundary ob_{};
  double rho0_ = 1;
  int dim_ = 3;
  Kernel kernel_;
  PeriodicBox pbox_;
  std::vector<std::uint8_t> buffer_;    ///< 1: inlet or outlet particle
  std::vector<std::uint8_t> conveyor_;  ///< inlet particle holding a conveyor slot (saved)
  std::vector<double> holes_;           ///< empty conveyor slots, 3 coordinates each (saved)
  /// apply() scratch: fluid next to a buffer face, hole order, outlet particles
  std::vector<std::uint32_t> face_fluid_, hole_order_, outlets_;
};

}  // namespace sadr::fluid
