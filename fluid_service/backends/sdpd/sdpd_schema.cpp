// SPDX-License-Identifier: MIT
// The "sdpd" entry of the backend schema (sadr/fluid/backend_schema.hpp): plain data, linked by
// the orchestrator without the numerics.
#include <limits>

#include "sadr/fluid/backend_schema.hpp"

namespace sadr::fluid::schema {

Backend sdpd_backend() {
  constexpr double inf = std::numeric_limits<double>::infinity();
  Backend b;
  b.name = "sdpd";
  b.summary =
      "smoothed dissipative particle dynamics (Espanol & Revenga 2003) with deterministic "
      "reaction-diffusion; docs/fluid-core.md";
  b.capabilities = {
      true, true, true, true, {"stationary", "morris", "adami"}, {"lucy", "wendland_c2"}};
  b.capabilities.moving_walls = true;
  b.capabilities.body_forces = true;
  b.required = {"sound_speed", "shear_viscosity"};
  b.memory = {{710, 830, 900}, 490};  // measured 704, 821, 863-901 B; sadr 333-489 B
  b.cost = {{550, 550, 8800}};        // measured 2D median 547 ns (9 examples), 3D 8784; 1D: 2D's
  b.parameters = {
      {"density_diffusion", "dimensionless", 0.1, 0.0, inf, false, false,
       "Molteni-Colagrossi density diffusion delta (continuity density)"},
      {"diffusion_eps", "dimensionless", 0.01, 0.0, inf, false, false,
       "eps in r^2/(r^2 + eps h^2) of the species Laplacian (as the SSA graph)"},
      {"density_band", "dimensionless", 0.5, 0.0, 1.0, false, true,
       "blow-up band: |rho/rho_0 - 1| must stay below it"},
      {"neighbor_skin", "dimensionless", 0.15, 0.0, 1.0, false, false,
       "Verlet skin as a fraction of h"},
      {"transport_velocity",
       "-",
       0,
       0,
       1,
       true,
       false,
       "on: the transport-velocity formulation (Adami, Hu & Adams 2013), particles move with "
       "v plus a shift from the uniform pressure shift_pressure (docs/fluid-core.md)",
       {"off", "on"}},
      {"shift_pressure", "dimensionless", 5.0, 0.0, inf, false, false,
       "transport velocity: the shift pressure p_b in units of rho_0 c_0^2"},
  };
  return b;
}

}  // namespace sadr::fluid::schema
