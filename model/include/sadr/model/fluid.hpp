// SPDX-License-Identifier: MIT
/// \file fluid.hpp
/// The fluid settings of a model, by name: the backend and its physical parameters, walls,
/// an open channel, Boussinesq buoyancy. The scene loader produces them (checked against the
/// backend's schema), the wire layer carries them (wire/model_proto.hpp) and fluid_service
/// compiles them to its FluidModel.
///
/// Units: one consistent system chosen by the scene author; "d" is the dimension.
#pragma once

#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace sadr::model {

/// Boussinesq body force g_b beta (C_s - C_ref) along `direction`.
struct Boussinesq {
  std::string species;
  double coefficient = 0.0;                        ///< g_b * beta [length^(d+2)/(time^2 molecules)]
  double reference = 0.0;                          ///< C_ref [molecules/length^d]
  std::array<double, 3> direction{0.0, 1.0, 0.0};  ///< unit vector
};

/// The wall surface of a region of wall particles (fluid.wall_planes; Morris walls): a plane,
/// or with radius > 0 a circle (2D) / sphere (3D) around `point` with the fluid outside.
struct WallPlane {
  std::string region;
  std::array<double, 3> point{};   ///< a point on the plane, or the centre [length]
  std::array<double, 3> normal{};  ///< plane: unit normal from the wall into the fluid
  double radius = 0.0;             ///< > 0: circle / sphere of this radius [length]
};

/// fluid.open_boundary (sdpd): an open channel along `axis` (docs/scene-format.md). Inlet buffer
/// [inlet_lo, fluid_lo), fluid [fluid_lo, fluid_hi), outlet buffer [fluid_hi, outlet_hi].
struct OpenBoundarySettings {
  int axis = 0;
  double inlet_lo = 0, fluid_lo = 0, fluid_hi = 0, outlet_hi = 0;  ///< [length]
  bool parabolic = false;           ///< profile: parabolic (else uniform)
  double mean_velocity = 0;         ///< mean inflow speed along +axis [length/time]
  int cross_axis = 1;               ///< parabolic: the axis across the channel
  double wall_lo = 0, wall_hi = 0;  ///< parabolic: its no-slip planes [length]
};

struct FluidSettings {
  std::string backend = "sdpd";   ///< "sdpd", "static" or "tdpd"
  double smoothing_length = 0.0;  ///< h [length]
  std::string kernel = "lucy";
  double reference_density = 1.0;           ///< rho_0 [mass/length^d]
  double sound_speed = 0.0;                 ///< c_0 [length/time] (sdpd)
  double shear_viscosity = 0.0;             ///< eta [mass/(length^(d-2) time)]
  double temperature = 0.0;                 ///< k_B T [energy]; 0 = no thermal noise
  std::array<double, 3> gravity{};          ///< body force per mass [length/time^2]
  std::string density_mode = "continuity";  ///< "continuity" or "summation"
  std::optional<Boussinesq> boussinesq;
  double max_time_step = 0.0;  ///< upper bound on the fluid sub-step [time]; 0 = none
  bool force_time_step = false;
  std::map<std::string, double> parameters;  ///< backend-specific numbers
  std::map<std::string, std::string> files;  ///< backend-specific files: absolute paths
  std::string wall_model = "stationary";     ///< one of the backend's wall models
  std::vector<WallPlane> wall_planes;        ///< wall_model "morris": one per wall region
  std::optional<OpenBoundarySettings> open_boundary;
  /// Regions of wall particles whose hydrodynamic force and torque the fluid reports
  /// (fluid.body_forces; sdpd), in scene order.
  std::vector<std::string> body_forces;
};

}  // namespace sadr::model
