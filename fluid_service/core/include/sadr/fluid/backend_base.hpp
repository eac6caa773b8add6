// SPDX-License-Identifier: MIT
/// \file backend_base.hpp
/// The lifecycle every fluid backend shares (docs/fluid-core.md, "The backend seam"). The
/// fluid core owns: validating the initial state, the concentration fields behind
/// concentrations()/set_concentrations(), the state-blob header and its versions (including
/// the layouts written before the core owned them), the advance() argument checks and the
/// NumericalFailure reports. A backend derived from BackendBase supplies only its set-up, its
/// stepping (rates and integrator), its read-out and its own state in the blob.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sadr/fluid/fluid_backend.hpp"
#include "sadr/fluid/periodic_box.hpp"
#include "sadr/fluid/species_transport.hpp"
#include "sadr/fluid/state_blob.hpp"

namespace sadr::fluid {

/// Checks `initial` and `concentrations` against `model` (not the model itself): the state's
/// own validate(), its dimension, 1 <= N <= 2^32 - 16, one field of N finite values per model
/// species (or none). InvalidArgument prefixed with the backend's name, naming field, value and
/// range.
void validate_initial_state(std::string_view backend, const FluidModel& model,
                            const ParticleState& initial,
                            const std::vector<std::vector<double>>& concentrations);

/// advance() arguments: time_step finite and > 0; step_index < 2^32 (the noise key of a
/// sub-step is (step_index << 16) | sub-step).
void validate_advance(std::string_view backend, std::uint64_t step_index, double time_step);

/// One failed health check. `limit` says what the value broke ("non-finite", "outside
/// rho_0 (1 +- 0.5)", "left the box on a walled axis").
struct HealthFailure {
  std::string_view backend;
  std::uint64_t step = 0;
  std::uint32_t substep = 0;
  std::uint64_t particle_id = 0;
  std::string field;  ///< "position[0]", "velocity[2]", "density", "concentration[A]"
  double value = 0.0;
  std::string limit;
};
/// Throws NumericalFailure "<backend> blow-up at step S sub-step K: particle id P <field> =
/// <value> (<limit>)" with details step, substep, particle_id, field, value, limit.
[[noreturn]] void throw_numerical_failure(const HealthFailure& f);

/// What the shared health check looks at (all arrays by particle index).
struct HealthView {
  const std::vector<double>& x;  ///< positions, 3N
  const std::vector<double>& v;  ///< velocities, 3N
  const std::vector<std::vector<double>>& c;
  const std::vector<SpeciesSpec>& species;
  const std::vector<std::uint64_t>& ids;  ///< particle ids (empty: the index)
  const PeriodicBox& box;
  const std::vector<double>* rho = nullptr;        ///< densities checked against the band, if given
  double rho0 = 1.0, band = 0.0;                   ///< |rho/rho0 - 1| <= band
  const std::vector<int>* only_species = nullptr;  ///< checked species (nullptr: all)
};
/// The first unhealthy particle (lowest index; checks in the order position, velocity,
/// density, walled-axis box, concentrations) as a NumericalFailure; nothing if all are finite
/// and inside. The scan is parallel above kMinParallelLight particles; the report does not
/// depend on the thread count.
void check_health(std::string_view backend, const HealthView& h, std::uint64_t step,
                  std::uint32_t substep);

/// Blob header of format 1: "sadr.fluid.state", format, backend name, backend state version.
void write_blob_header(BlobWriter& w, std::string_view backend, std::uint32_t version);
/// Reads a header written by write_blob_header() or one of the per-backend headers written
/// before it (sdpd and static: 64-bit tag, version, name; tdpd: "sadr.tdpd", version; the state
/// after them is laid out as it is now). Returns the backend state version; InvalidArgument if
/// the blob is not a fluid state or was written by another backend.
std::uint32_t read_blob_header(BlobReader& r, std::string_view backend);

/// FluidBackend with the shared lifecycle (see the file comment). Derived classes implement the
/// protected hooks; the public calls check initialisation and arguments first.
class BackendBase : public FluidBackend {
 public:
  void initialize(const FluidModel& model, const ParticleState& initial,
                  const std::vector<std::vector<double>>& concentrations) final;
  StepReport advance(std::uint64_t step_index, double time_step) final;
  void read_state(ParticleState& out) const final;
  [[nodiscard]] const std::vector<double>& concentrations(int species) const final;
  /// Checks N finite values, stores them, re-imposes the Dirichlet wall values, then
  /// concentrations_changed().
  void set_concentrations(int species, std::span<const double> values) final;
  [[nodiscard]] std::string save() const final;
  void restore(std::string_view blob) final;

 protected:
  /// FailedPrecondition "<backend>: <what> before initialize()".
  void require_initialized(const char* what) const;
  /// The model checks (default: FluidModel::validate()).
  virtual void check_model(const FluidModel& model) const { model.validate(); }
  /// Set-up after the shared checks passed; time = 0 afterwards.
  virtual void setup(const FluidModel& model, const ParticleState& initial,
                     const std::vector<std::vector<double>>& concentrations) = 0;
  /// advance() after the argument checks.
  virtual StepReport step(std::uint64_t step_index, double time_step) = 0;
  virtual void write_state(ParticleState& out) const = 0;
  /// The concentration fields [species][N] and the transport that knows their wall values.
  [[nodiscard]] virtual std::vector<std::vector<double>>& fields() = 0;
  [[nodiscard]] virtual const std::vector<std::vector<double>>& fields() const = 0;
  [[nodiscard]] virtual const SpeciesTransport& transport() const = 0;
  /// After set_concentrations() (e.g. cached rates are stale).
  virtual void concentrations_changed() {}
  /// The backend's state after the header, and its version.
  [[nodiscard]] virtual std::uint32_t state_version() const = 0;
  virtual void save_state(BlobWriter& w) const = 0;
  /// Reads what save_state() of `version` wrote; calls r.expect_end() before it changes any
  /// member (a refused blob leaves the backend as it was).
  virtual void restore_state(BlobReader& r, std::uint32_t version) = 0;

 private:
  bool initialized_ = false;
};

}  // namespace sadr::fluid
