// SPDX-License-Identifier: MIT
#include "service_set.hpp"

#include <unistd.h>

#include <filesystem>

#include "sadr/fluid/fluid_service.hpp"
#include "sadr/ssa/ssa_service.hpp"

namespace sadr::orchestrator {

std::string_view to_string(ServiceMode mode) {
  switch (mode) {
    case ServiceMode::kProcesses:
      return "processes";
    case ServiceMode::kEmbedded:
      return "embedded";
    case ServiceMode::kRemote:
      return "remote";
  }
  return "unknown";
}

namespace {
std::string unique_name(const std::string& service, const std::string& tag) {
  return "sadr-" + std::to_string(getpid()) + "-" + tag + "-" + service;
}
}  // namespace

ServiceSet::ServiceSet(ServiceMode mode, const Plan& plan, const ServiceEndpoints& remote,
                       const std::string& tag)
    : mode_(mode) {
  struct Need {
    bool needed;
    const char* name;
    const char* exe;
    std::string* endpoint;
    const std::string* remote;
  };
  const Need needs[] = {
      {plan.fluid_service, "fluid", "fluid_service", &endpoints_.fluid, &remote.fluid},
      {plan.ssa_service, "ssa", "ssa_service", &endpoints_.ssa, &remote.ssa}};
  for (const Need& n : needs) {
    if (!n.needed) continue;
    switch (mode_) {
      case ServiceMode::kRemote:
        if (n.remote->empty()) {
          throw InvalidArgument(std::string("--") + n.name +
                                " ENDPOINT is required with remote "
                                "services: the scene needs " +
                                n.exe);
        }
        *n.endpoint = *n.remote;
        break;
      case ServiceMode::kProcesses: {
        const std::string path = std::filesystem::temp_directory_path() / unique_name(n.name, tag);
        ipc_files_.push_back(path);
        const std::string exe = executable_dir() + "/" + n.exe;
        processes_.push_back(std::make_unique<ServiceProcess>(
            exe, std::vector<std::string>{"--endpoint", "ipc://" + path, "--log-level", "warn"},
            n.exe));
        *n.endpoint = processes_.back()->endpoint();
        break;
      }
      case ServiceMode::kEmbedded: {
        wire::ServerOptions o;
        o.endpoint = "inproc://" + unique_name(n.name, tag);
        o.kind = std::string_view(n.name) == "fluid" ? common::v1::SERVICE_KIND_FLUID
                                                     : common::v1::SERVICE_KIND_SSA;
        servers_.push_back(std::make_unique<wire::RpcServer>(o));
        if (o.kind == common::v1::SERVICE_KIND_FLUID) {
          handlers_.push_back(std::make_unique<fluid::FluidServiceHandler>());
        } else {
          handlers_.push_back(std::make_unique<ssa::SsaServiceHandler>());
        }
        *n.endpoint = servers_.back()->endpoint();
        wire::RpcServer* server = servers_.back().get();
        wire::RequestHandler* handler = handlers_.back().get();
        threads_.emplace_back([this, server, handler] { server->serve(*handler, &stop_threads_); });
        break;
      }
    }
  }
}

ServiceSet::~ServiceSet() {
  stop();
}

void ServiceSet::check_alive() {
  std::lock_guard lock(alive_mutex_);
  for (auto& p : processes_) {
    if (!p->alive()) {
      throw Error(StatusCode::kUnavailable,
                  p->name() + " (pid " + std::to_string(p->pid()) + ") died: " + p->describe());
    }
  }
}

void ServiceSet::stop() {
  stop_threads_ = true;
  for (auto& t : threads_) {
    if (t.joinable()) t.join();
  }
  threads_.clear();
  for (auto& p : processes_) p->terminate();
  processes_.clear();
  for (const auto& f : ipc_files_) std::filesystem::remove(f);
  ipc_files_.clear();
}

}  // namespace sadr::orchestrator
