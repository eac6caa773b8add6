// SPDX-License-Identifier: MIT
/// \file prescribed_backend.hpp
/// "prescribed": particles carried by a velocity field given in the scene (no fluid solve), for
/// a user with a known flow. Fields (fluid.parameters, `field`; the scene writes the name, the
/// backend gets its index): 0 uniform u = (ux, uy, uz); 1 shear u_x = shear_rate (y - y0);
/// 2 poiseuille u_x = 4 u_max (y - a)(b - y)/(b - a)^2 between the planes y = a, b (wall_lo,
/// wall_hi; 0 outside); 3 rotation (solid body) about (cx, cy) in the x-y plane,
/// u = omega (-(y - cy), x - cx); 4 csv: read from the file `field_file` and interpolated
/// multilinearly (prescribed_grid.hpp; RK4 only). Integrated exactly (the flow map of each field in
/// closed form; `integrator` 0, "exact") or with classical RK4 (`integrator` 1, "rk4") in sub-steps
/// no longer than max_time_step. Wall particles never move. Deterministic species follow the SDPD
/// species operator (species_operator.hpp, as static) at the positions after each advance (Lie
/// splitting of the Lagrangian transport: first order in the coupling step). No thermal noise:
/// molecules diffuse in ssa_service on the particle graph. The fields are evaluated at unwrapped
/// positions within a step (periodic axes wrap after it), so a field that is not periodic itself
/// (shear across a periodic y) is the user's to avoid.
#pragma once

#include <array>
#include <map>
#include <memory>
#include <string>

#include "prescribed_grid.hpp"
#include "sadr/fluid/backend_base.hpp"
#include "sadr/fluid/backend_registry.hpp"
#include "sadr/fluid/species_operator.hpp"

namespace sadr::fluid {

/// A steady velocity field and its flow map.
struct PrescribedField {
  enum class Kind { kUniform = 0, kShear = 1, kPoiseuille = 2, kRotation = 3, kGrid = 4 };
  Kind kind = Kind::kUniform;
  std::array<double, 3> u{0, 0, 0};                   ///< uniform velocity [length/time]
  double shear_rate = 0, y0 = 0;                      ///< [1/time], [length]
  double max_velocity = 0, wall_lo = 0, wall_hi = 1;  ///< Poiseuille [length/time], [length]
  double omega = 0, cx = 0, cy = 0;                   ///< rotation [1/time], centre [length]
  std::shared_ptr<const GridField> grid;              ///< csv
  /// Reads fluid.parameters and the field file (InvalidArgument naming an unknown key, a bad
  /// value or what in the file is not a grid).
  static PrescribedField from_model(const FluidModel& model, bool& rk4);
  /// v = u(x); csv: an Error (OUT_OF_RANGE) when x lies outside the grid on a walled axis.
  void velocity(const double* x, double* v) const;
  /// x <- the exact flow map over dt.
  void exact(double* x, double dt) const;
  /// x <- one classical RK4 step of length dt.
  void rk4(double* x, double dt) const;
};

class PrescribedBackend final : public BackendBase {
 public:
  [[nodiscard]] std::string_view name() const override { return "prescribed"; }
  [[nodiscard]] double time() const override { return time_; }
  [[nodiscard]] const PrescribedField& field() const { return field_; }
  /// The species operator's limits (diffusion, reaction) at the current positions under
  /// max_time_step / force_time_step, or, without transported species, RK4's moves of at most
  /// max_time_step (the exact map: one piece).
  [[nodiscard]] SubstepBound current_substep_bound() override;

 protected:
  void setup(const FluidModel& model, const ParticleState& initial,
             const std::vector<std::vector<double>>& concentrations) override;
  StepReport step(std::uint64_t step_index, double time_step) override;
  void write_state(ParticleState& out) const override { out = state_; }
  std::vector<std::vector<double>>& fields() override { return c_; }
  const std::vector<std::vector<double>>& fields() const override { return c_; }
  const SpeciesTransport& transport() const override { return species_.transport(); }
  std::uint32_t state_version() const override { return 1; }
  void save_state(BlobWriter& w) const override;
  void restore_state(BlobReader& r, std::uint32_t version) override;

 private:
  void move(double dt);  ///< fluid particles by dt (exact, or RK4 in sub-steps), v = u(x)
  void set_velocity(std::size_t i);  ///< v_i = u(x_i) (an Error naming i off a csv grid)
  FluidModel model_;
  PrescribedField field_;
  bool rk4_ = false;
  PeriodicBox pbox_;
  ParticleState state_;
  std::vector<std::vector<double>> c_;
  SpeciesOperator species_;
  double time_ = 0;
  std::uint64_t step_ = 0;  ///< the step being taken (for messages)
};

/// Registers "prescribed" (called by the generated register_builtin_backends(), backends.cmake).
void register_prescribed_backend(BackendRegistry& registry);

}  // namespace sadr::fluid
