// SPDX-License-Identifier: MIT
#include "sadr/fluid/backend_registry.hpp"

#include "sadr/common/status.hpp"

namespace sadr::fluid {

void BackendRegistry::add(std::string name, Factory factory) {
  if (name.empty()) throw InvalidArgument("backend name must not be empty");
  if (!factory) throw InvalidArgument("backend '" + name + "': factory must not be empty");
  if (factories_.contains(name))
    throw InvalidArgument("backend '" + name + "' is already registered");
  factories_.emplace(std::move(name), std::move(factory));
}

std::unique_ptr<FluidBackend> BackendRegistry::create(std::string_view name) const {
  const auto it = factories_.find(name);
  if (it == factories_.end()) {
    std::string known;
    for (const auto& [n, f] : factories_) known += (known.empty() ? "" : ", ") + n;
    throw InvalidArgument("unknown fluid backend '" + std::string(name) +
                              "' (known: " + (known.empty() ? "none registered" : known) + ")",
                          {{"field", "backend"}, {"value", std::string(name)}});
  }
  return it->second();
}

std::vector<std::string> BackendRegistry::names() const {
  std::vector<std::string> out;
  for (const auto& [n, f] : factories_) out.push_back(n);
  return out;
}

bool BackendRegistry::contains(std::string_view name) const {
  return factories_.find(name) != factories_.end();
}

}  // namespace sadr::fluid
