// SPDX-License-Identifier: MIT
// The "prescribed" entry of the backend schema (sadr/fluid/backend_schema.hpp).
#include <limits>

#include "sadr/fluid/backend_schema.hpp"

namespace sadr::fluid::schema {

Backend prescribed_backend() {
  constexpr double inf = std::numeric_limits<double>::infinity();
  Backend b;
  b.name = "prescribed";
  b.summary =
      "particles carried by a velocity field given in the scene (no fluid solve), exactly "
      "or with RK4; docs/fluid-core.md";
  b.capabilities = {true, true, false, false, {"stationary"}, {"lucy", "wendland_c2"}};
  b.memory = {{710, 830, 900}, 490};  // not measured: sdpd's figures (it holds less)
  b.cost = {{2000, 2000, 2000}};      // measured 2D 2040 ns (species and reactions); 1D, 3D: 2D's
  b.parameters = {
      {"field",
       "-",
       0,
       0,
       4,
       true,
       false,
       "uniform (ux, uy, uz); shear u_x = shear_rate (y - y0); poiseuille between y = wall_lo, "
       "wall_hi; rotation: solid body, omega about (cx, cy); csv: read from field_file",
       {"uniform", "shear", "poiseuille", "rotation", "csv"}},
      {"field_file",
       "-",
       0,
       0,
       0,
       false,
       false,
       "csv: the field on a grid, columns x, y, z, ux, uy, uz (the active ones), interpolated "
       "multilinearly (docs/scene-format.md)",
       {},
       true},
      {"integrator",
       "-",
       0,
       0,
       1,
       true,
       false,
       "exact: the flow map (not for csv); rk4: classical RK4 in sub-steps <= max_time_step",
       {"exact", "rk4"}},
      {"ux", "length/time", 0, -inf, inf, false, false, "uniform velocity, x"},
      {"uy", "length/time", 0, -inf, inf, false, false, "uniform velocity, y"},
      {"uz", "length/time", 0, -inf, inf, false, false, "uniform velocity, z"},
      {"shear_rate", "1/time", 0, -inf, inf, false, false, "simple shear rate"},
      {"y0", "length", 0, -inf, inf, false, false, "shear: the plane of zero velocity"},
      {"max_velocity", "length/time", 0, -inf, inf, false, false, "Poiseuille: centre velocity"},
      {"wall_lo", "length", 0, -inf, inf, false, false, "Poiseuille: lower no-slip plane y"},
      {"wall_hi", "length", 1, -inf, inf, false, false, "Poiseuille: upper no-slip plane y"},
      {"omega", "1/time", 0, -inf, inf, false, false, "rotation: angular velocity"},
      {"cx", "length", 0, -inf, inf, false, false, "rotation: centre x"},
      {"cy", "length", 0, -inf, inf, false, false, "rotation: centre y"},
  };
  return b;
}

}  // namespace sadr::fluid::schema
