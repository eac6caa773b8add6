// SPDX-License-Identifier: MIT
#include "sadr/wire/service_main.hpp"

#include <unistd.h>
#include <CLI/CLI.hpp>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <thread>

#include "sadr/common/log.hpp"
#include "sadr/common/version.hpp"
#include "sadr/wire/curve_keys.hpp"
#include "sadr/wire/shared_geometry.hpp"

namespace sadr::wire {
namespace {

std::atomic<bool> g_stop{false};
extern "C" void on_signal(int) {
  g_stop.store(true);
}

log::Level parse_level(const std::string& s) {
  if (s == "error") return log::Level::kError;
  if (s == "warn") return log::Level::kWarn;
  if (s == "debug") return log::Level::kDebug;
  return log::Level::kInfo;
}

/// What a service leaves on the file system: its ipc socket file, the run
/// directory holding it (removed when empty) and, when its parent died, the
/// parent's geometry segments (nobody else can unlink them any more).
void remove_traces(const std::string& endpoint, long dead_parent) {
  constexpr std::string_view kIpc = "ipc://";
  if (endpoint.rfind(kIpc, 0) == 0) {
    const std::filesystem::path socket = endpoint.substr(kIpc.size());
    std::error_code ec;
    std::filesystem::remove(socket, ec);
    if (socket.parent_path().filename().string().rfind("sadr-run-", 0) == 0) {
      std::filesystem::remove(socket.parent_path(), ec);  // only if empty
    }
  }
  if (dead_parent > 0) remove_segments_of(dead_parent);
}

/// Stops the process within about a second, even inside a long request, when
/// the sadr that launched it dies (SADR_PARENT_PID, no longer our parent) or
/// when a stop signal is not honoured within 0.8 s (the serve loop only sees
/// it between requests): removes its traces, then _exit. A clean shutdown
/// returns from main before the watchdog acts.
void start_watchdog(const std::string& name, const std::string& endpoint) {
  const char* v = std::getenv("SADR_PARENT_PID");
  const long parent = v ? std::atol(v) : 0;
  std::thread([name, endpoint, parent] {
    int stopping_ticks = 0;
    for (;;) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      const bool orphan = parent > 0 && static_cast<long>(getppid()) != parent;
      if (g_stop.load()) ++stopping_ticks;
      if (!orphan && stopping_ticks < 8) continue;
      remove_traces(endpoint, orphan ? parent : 0);
      log::warn(name, orphan ? ": the sadr that launched it (pid " + std::to_string(parent) +
                                   ") died; exiting"
                             : std::string(": stop signal during a request; exiting"));
      std::_Exit(orphan ? 1 : 0);
    }
  }).detach();
}

}  // namespace

void serve_forever(RpcServer& server, RequestHandler& handler, const std::atomic<bool>* stop) {
  server.serve(handler, stop);
}

int run_service_main(int argc, char** argv, common::v1::ServiceKind kind,
                     const std::function<std::unique_ptr<RequestHandler>()>& make_handler) {
  const std::string name(service_name(kind));
  CLI::App app{name + " " + kVersion + ": a sadr service speaking wire protocol v" +
               std::to_string(kProtocolVersion) +
               ". Normally started by the orchestrator ('sadr run'); start it by hand only to "
               "serve a remote orchestrator ('sadr run --fluid/--ssa ENDPOINT')."};
  std::string endpoint = "tcp://127.0.0.1:*";
  std::int64_t max_mb = 2047;
  std::string level = "info";
  app.add_option("--endpoint", endpoint,
                 "ZeroMQ endpoint to bind: tcp://HOST:PORT (PORT * = ephemeral), ipc:///path")
      ->capture_default_str();
  app.add_option("--max-message-mb", max_mb, "largest accepted message [MiB]")
      ->check(CLI::Range(1, 2047))
      ->capture_default_str();
  std::string key_file, authorized_file;
  auto* key_opt = app.add_option("--key", key_file,
                                 "CURVE key pair of this service (from 'sadr keygen FILE'): tcp "
                                 "traffic is encrypted and only --authorized-keys clients get in");
  auto* auth_opt = app.add_option("--authorized-keys", authorized_file,
                                  "public keys of the clients this service accepts, one per "
                                  "line (the FILE.pub of each client's 'sadr keygen')");
  key_opt->needs(auth_opt);
  auth_opt->needs(key_opt);
  bool insecure_bind = false;
  app.add_flag("--insecure-bind", insecure_bind,
               "allow a tcp endpoint on a non-loopback address without --key: anyone who can "
               "reach it can read and change the run (docs/cli.md, \"Security\")");
  app.add_option("--log-level", level, "error|warn|info|debug")
      ->check(CLI::IsMember({"error", "warn", "info", "debug"}))
      ->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : 2;
  }
  log::set_component(name);
  log::set_level(parse_level(level));
  if (key_file.empty() && !insecure_bind && !is_local_endpoint(endpoint)) {
    std::fprintf(stderr,
                 "%s: refusing to bind '%s': a tcp endpoint on a non-loopback address needs "
                 "CURVE keys (--key FILE --authorized-keys FILE, made by 'sadr keygen'): "
                 "without them anyone who reaches it can read the particles and stop the run. "
                 "Or bind tcp://127.0.0.1:PORT and reach it through an ssh tunnel, or pass "
                 "--insecure-bind on a network you trust (docs/cli.md, \"Security\")\n",
                 name.c_str(), shorten(endpoint).c_str());
    return 2;
  }
  std::optional<CurveServerKeys> curve;
  if (!key_file.empty()) {
    try {
      if (!curve_available()) throw Error(StatusCode::kUnavailable, "this libzmq has no CURVE");
      curve = CurveServerKeys{read_key_file(key_file), read_authorized_keys(authorized_file)};
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: %s\n", name.c_str(), e.what());
      return 2;
    }
  }
  std::signal(SIGTERM, on_signal);
  std::signal(SIGINT, on_signal);
  std::signal(SIGPIPE, SIG_IGN);
  try {
    auto handler = make_handler();
    ServerOptions options;
    options.endpoint = endpoint;
    options.kind = kind;
    options.max_message_bytes = max_mb * 1024 * 1024;
    options.curve = curve;
    // The per-run secret of the sadr that launched us (never on the command
    // line, where every user could read it): taken, then wiped from our
    // environment block (/proc/PID/environ).
    if (char* secret = std::getenv("SADR_RUN_SECRET"); secret != nullptr && *secret != '\0') {
      if (!curve) options.secret = secret;
      std::memset(secret, 'x', std::strlen(secret));
      unsetenv("SADR_RUN_SECRET");
    }
    RpcServer server(options);
    std::printf("SADR_ENDPOINT %s\n", server.endpoint().c_str());
    std::fflush(stdout);
    log::info(name, " ", kVersion, " (pid ", getpid(), ") serving on ", server.endpoint(),
              curve ? " (CURVE, " + std::to_string(curve->authorized_clients.size()) +
                          " authorized client keys)"
              : options.secret.empty() ? " (no authentication)"
                                       : " (run secret)");
    start_watchdog(name, server.endpoint());
    serve_forever(server, *handler, &g_stop);
    remove_traces(server.endpoint(), 0);
    log::info(name, g_stop.load() ? " stopped by signal" : " shut down on request");
    return 0;
  } catch (const std::exception& e) {
    log::error(name, " failed: ", e.what());
    return 1;
  }
}

}  // namespace sadr::wire
