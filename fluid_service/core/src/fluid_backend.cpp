// SPDX-License-Identifier: MIT
#include "sadr/fluid/fluid_backend.hpp"

#include <string>

#include "sadr/common/status.hpp"

namespace sadr::fluid {

const schema::Capabilities& FluidBackend::capabilities() const {
  const schema::Backend* entry = schema::find(name());
  if (entry == nullptr) {
    throw Error(StatusCode::kInternal, "fluid backend '" + std::string(name()) +
                                           "' has no entry in the backend schema (" +
                                           schema::names() + ")");
  }
  return entry->capabilities;
}

}  // namespace sadr::fluid
