// SPDX-License-Identifier: MIT
// The "tdpd" entry of the backend schema (sadr/fluid/backend_schema.hpp); the defaults are those
// of TdpdParameters (tdpd_backend.hpp, checked by tests/fluid/backend_schema_test.cpp).
#include <limits>

#include "sadr/fluid/backend_schema.hpp"

namespace sadr::fluid::schema {

Backend tdpd_backend() {
  constexpr double inf = std::numeric_limits<double>::infinity();
  Backend b;
  b.name = "tdpd";
  b.summary = "transport dissipative particle dynamics (Li et al. 2015), DPD units; docs/tdpd.md";
  b.capabilities = {true, true, true, false, {"stationary"}, {"lucy"}};
  // tdpd_rates.cpp integrates no wall particle (their concentrations never change) and
  // effective walls turn `free` into no flux, so wall reactions and `free` walls are refused.
  b.capabilities.wall_species_terms = false;
  // Its species step (tdpd_rates.cpp) has no per-particle boundary source and its Neumann flux
  // lives on the effective walls: boundary fluxes of deterministic species are refused.
  b.capabilities.boundary_fluxes = false;
  b.memory = {{710, 710, 820}, 570};  // measured 2D 705, 3D 818 B; sadr 556-566 B
  b.cost = {{550, 550, 9500}};        // measured 3D 9472 ns; 1D, 2D not measured: sdpd's
  b.parameters = {
      {"a", "force", 18.75, 0.0, inf, false, false, "conservative force amplitude a_ij"},
      {"gamma", "mass/time", 4.5, 0.0, inf, false, false, "dissipative coefficient"},
      {"s1", "dimensionless", 0.41, 0.0, inf, false, false, "exponent of the dissipative weight"},
      {"r_cc", "length", 0.0, 0.0, inf, false, false,
       "concentration-flux cutoff, <= smoothing_length (0: smoothing_length)"},
      {"lambda", "dimensionless", 0.5, 0.0, 1.0, false, false,
       "Groot-Warren velocity-prediction factor"},
      {"skin", "dimensionless", 0.3, 0.0, 1.0, false, false,
       "Verlet skin as a fraction of r_c (0: neighbor_skin)"},
      {"neighbor_skin", "dimensionless", 0.15, 0.0, 1.0, false, false,
       "Verlet skin used when skin = 0"},
      {"effective_walls", "-", 0.0, 0.0, 1.0, true, false,
       "1: walls without frozen particles on the non-periodic faces (li2015 sec. II B)"},
      {"buffer_axis", "-", -1.0, -1.0, 2.0, true, false,
       "periodic axis of the concentration inflow/outflow buffers (-1: none)"},
      {"inflow_length", "length", 0.0, 0.0, inf, false, false,
       "inflow buffer length from box.lo along buffer_axis"},
      {"inflow_value", "C", 0.0, -inf, inf, false, false,
       "concentration held in the inflow buffer"},
  };
  return b;
}

}  // namespace sadr::fluid::schema
