// SPDX-License-Identifier: MIT
#include "sadr/wire/service_main.hpp"

#include <unistd.h>
#include <CLI/CLI.hpp>
#include <csignal>
#include <cstdio>

#include "sadr/common/log.hpp"
#include "sadr/common/version.hpp"

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
  std::signal(SIGTERM, on_signal);
  std::signal(SIGINT, on_signal);
  std::signal(SIGPIPE, SIG_IGN);
  try {
    auto handler = make_handler();
    ServerOptions options;
    options.endpoint = endpoint;
    options.kind = kind;
    options.max_message_bytes = max_mb * 1024 * 1024;
    RpcServer server(options);
    std::printf("SADR_ENDPOINT %s\n", server.endpoint().c_str());
    std::fflush(stdout);
    log::info(name, " ", kVersion, " (pid ", getpid(), ") serving on ", server.endpoint());
    serve_forever(server, *handler, &g_stop);
    log::info(name, g_stop.load() ? " stopped by signal" : " shut down on request");
    return 0;
  } catch (const std::exception& e) {
    log::error(name, " failed: ", e.what());
    return 1;
  }
}

}  // namespace sadr::wire
