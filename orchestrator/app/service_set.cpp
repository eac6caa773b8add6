// SPDX-License-Identifier: MIT
#include "service_set.hpp"

#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "sadr/fluid/fluid_service.hpp"
#include "sadr/ssa/ssa_service.hpp"
#include "sadr/wire/shared_geometry.hpp"

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
/// A new directory only this user can open, for the run's ipc sockets:
/// <tmp>/sadr-run-<pid>-XXXXXX (mkdtemp: mode 0700).
std::filesystem::path make_run_directory() {
  std::string templ = (std::filesystem::temp_directory_path() /
                       ("sadr-run-" + std::to_string(getpid()) + "-XXXXXX"))
                          .string();
  if (::mkdtemp(templ.data()) == nullptr) {
    throw IoError("cannot create a run directory '" + templ + "': " + std::strerror(errno));
  }
  return templ;
}

/// 32 random bytes as hex: the secret that only this run's services accept.
std::string make_run_secret() {
  unsigned char bytes[32];
  std::FILE* f = std::fopen("/dev/urandom", "rb");
  const bool ok = f != nullptr && std::fread(bytes, 1, sizeof bytes, f) == sizeof bytes;
  if (f != nullptr) std::fclose(f);
  if (!ok) throw IoError("cannot read /dev/urandom for the run's secret");
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  for (const unsigned char b : bytes) {
    out.push_back(kHex[b >> 4]);
    out.push_back(kHex[b & 15]);
  }
  return out;
}

bool process_gone(long pid) {
  return pid > 0 && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
}
}  // namespace

std::size_t remove_traces_of_dead_runs() {
  std::size_t n = wire::remove_segments_of_dead_processes();
  std::error_code ec;
  const auto tmp = std::filesystem::temp_directory_path(ec);
  if (ec) return n;
  for (const auto& e : std::filesystem::directory_iterator(tmp, ec)) {
    const std::string name = e.path().filename().string();
    // sadr-run-<pid>-XXXXXX (run directories) and sadr-<pid>-... (sockets of
    // older builds); only this user's.
    const std::size_t at = name.rfind("sadr-run-", 0) == 0 ? 9
                           : name.rfind("sadr-", 0) == 0   ? 5
                                                           : 0;
    if (at == 0) continue;
    char* end = nullptr;
    const long pid = std::strtol(name.c_str() + at, &end, 10);
    if (*end != '-' || !process_gone(pid)) continue;
    struct stat st {};
    if (::lstat(e.path().c_str(), &st) != 0 || st.st_uid != ::getuid()) continue;
    n += std::filesystem::remove_all(e.path(), ec) > 0 ? 1 : 0;
  }
  return n;
}

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
        if (run_dir_.empty()) run_dir_ = make_run_directory();
        const std::string path = run_dir_ / (std::string(n.name) + "-" + tag);
        ipc_files_.push_back(path);
        const std::string exe = executable_dir() + "/" + n.exe;
        if (secret_.empty()) secret_ = make_run_secret();
        processes_.push_back(std::make_unique<ServiceProcess>(
            exe, std::vector<std::string>{"--endpoint", "ipc://" + path, "--log-level", "warn"},
            n.exe, std::chrono::seconds(20),
            std::vector<std::string>{"SADR_RUN_SECRET=" + secret_}));
        *n.endpoint = processes_.back()->endpoint();
        wire::set_client_secret(*n.endpoint, secret_);  // only our clients get in
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
  for (auto& p : processes_) {
    wire::set_client_secret(p->endpoint(), "");
    p->terminate();
  }
  processes_.clear();
  std::error_code ec;
  for (const auto& f : ipc_files_) std::filesystem::remove(f, ec);
  ipc_files_.clear();
  if (!run_dir_.empty()) std::filesystem::remove_all(run_dir_, ec);
  run_dir_.clear();
}

}  // namespace sadr::orchestrator
