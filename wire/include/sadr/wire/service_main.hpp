// SPDX-License-Identifier: MIT
/// \file service_main.hpp
/// The shared body of every service executable's main(): parse the command
/// line, bind, announce the endpoint, serve until shutdown or SIGTERM/SIGINT.
///
/// Command line: `--endpoint URL` (default tcp://127.0.0.1:* : loopback,
/// ephemeral port), `--max-message-mb N` (default 2047), `--log-level L`,
/// `--key FILE --authorized-keys FILE` (CURVE; required for a non-loopback
/// tcp address unless `--insecure-bind`).
/// Once bound, the service prints exactly one line to stdout,
/// `SADR_ENDPOINT <resolved endpoint>`, which a parent reads to connect.
/// Exit codes: 0 clean shutdown (request or signal), 1 cannot bind or
/// failed, 2 bad command line (or keys, or an unauthenticated non-loopback bind).
#pragma once

#include <atomic>
#include <functional>
#include <memory>

#include "sadr/wire/rpc.hpp"

namespace sadr::wire {

/// Runs a service process. `make_handler` is called once after argument
/// parsing, so handlers are created only for a real run (not for --help).
int run_service_main(int argc, char** argv, common::v1::ServiceKind kind,
                     const std::function<std::unique_ptr<RequestHandler>()>& make_handler);

/// Serves `handler` on `server` in the current thread until shutdown or `stop`.
/// Used by run_service_main and by the orchestrator's embedded mode (threads).
void serve_forever(RpcServer& server, RequestHandler& handler, const std::atomic<bool>* stop);

}  // namespace sadr::wire
