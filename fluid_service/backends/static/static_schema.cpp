// SPDX-License-Identifier: MIT
// The "static" entry of the backend schema (sadr/fluid/backend_schema.hpp).
#include <limits>

#include "sadr/fluid/backend_schema.hpp"

namespace sadr::fluid::schema {

Backend static_backend() {
  constexpr double inf = std::numeric_limits<double>::infinity();
  Backend b;
  b.name = "static";
  b.summary =
      "particles never move; the fluid service only integrates the deterministic species "
      "on them (SDPD's species operator)";
  b.capabilities = {false, true, false, false, {"stationary"}, {"lucy", "wendland_c2"}};
  b.memory = {{1250, 1250, 1330}, 490};  // measured 2D 1247, 3D 1322 B (1D: the 2D figure)
  b.cost = {{220, 120, 360}};            // measured 1D 215 ns, 2D 114; 3D not measured: 3x 2D's
  b.parameters = {
      {"diffusion_eps", "dimensionless", 0.01, 0.0, inf, false, false,
       "eps in r^2/(r^2 + eps h^2) of the species Laplacian (as the SSA graph)"},
  };
  return b;
}

}  // namespace sadr::fluid::schema
