// SPDX-License-Identifier: MIT
/// \file backend_registry.hpp
/// Explicit name -> factory registry of fluid backends (no static self-registration).
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "sadr/fluid/fluid_backend.hpp"

namespace sadr::fluid {

class BackendRegistry {
 public:
  using Factory = std::function<std::unique_ptr<FluidBackend>()>;
  /// Registers `factory` under `name`; InvalidArgument if the name is empty or taken.
  void add(std::string name, Factory factory);
  /// A new backend; InvalidArgument listing the known names if `name` is unknown.
  [[nodiscard]] std::unique_ptr<FluidBackend> create(std::string_view name) const;
  /// Registered names in lexicographic order.
  [[nodiscard]] std::vector<std::string> names() const;
  [[nodiscard]] bool contains(std::string_view name) const;

 private:
  std::map<std::string, Factory, std::less<>> factories_;
};

}  // namespace sadr::fluid
