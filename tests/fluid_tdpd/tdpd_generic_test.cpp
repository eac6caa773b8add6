// SPDX-License-Identifier: MIT
/// Instantiates the backend-generic property tests for "tdpd", "sdpd" and "static".
#include "backend_generic_test.hpp"
#include "sadr/fluid/builtin_backends.hpp"
#include "tdpd/tdpd_backend.hpp"

namespace sadr::fluid::generic_test {
namespace {

std::function<std::unique_ptr<FluidBackend>()> from_registry(std::string name) {
  return [name] {
    BackendRegistry reg;
    register_builtin_backends(reg);
    if (!reg.contains("tdpd")) register_tdpd_backend(reg);  // once the lead lists it
    return reg.create(name);
  };
}

BackendCase tdpd_case() {
  BackendCase c;
  c.name = "tdpd";
  c.make = from_registry("tdpd");
  return c;
}

BackendCase sdpd_case() {
  BackendCase c;
  c.name = "sdpd";
  c.make = from_registry("sdpd");
  c.smoothing_length = 1.58;
  c.reference_density = 4.0;  // mass 1 at number density 4
  c.sound_speed = 4.0;
  c.shear_viscosity = 1.0;
  c.temperature = 1e-3;
  c.time_step = 0.01;
  return c;
}

BackendCase static_case() {
  BackendCase c;
  c.name = "static";
  c.make = from_registry("static");
  c.temperature = 0.0;
  return c;
}

INSTANTIATE_TEST_SUITE_P(AllBackends, BackendGenericTest,
                         ::testing::Values(tdpd_case(), sdpd_case(), static_case()), case_name);

}  // namespace
}  // namespace sadr::fluid::generic_test
