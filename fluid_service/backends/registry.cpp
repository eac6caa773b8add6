// SPDX-License-Identifier: MIT
#include <memory>

#include "prescribed/prescribed_backend.hpp"
#include "sadr/fluid/builtin_backends.hpp"
#include "sdpd/sdpd_backend.hpp"
#include "static/static_backend.hpp"
#include "tdpd/tdpd_backend.hpp"

namespace sadr::fluid {

void register_builtin_backends(BackendRegistry& registry) {
  registry.add("prescribed", [] { return std::make_unique<PrescribedBackend>(); });
  registry.add("sdpd", [] { return std::make_unique<SdpdBackend>(); });
  registry.add("static", [] { return std::make_unique<StaticBackend>(); });
  register_tdpd_backend(registry);  // "tdpd" (backends/tdpd)
}

}  // namespace sadr::fluid
