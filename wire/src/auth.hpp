// SPDX-License-Identifier: MIT
/// \file auth.hpp
/// Private to sadr::wire: who may connect. One ZAP handler (RFC 27) per
/// process answers for every server socket that asked for a secret (PLAIN) or
/// for CURVE with a list of authorized client keys; clients look up the
/// credentials registered for their endpoint (set_client_credentials).
#pragma once

#include <string>
#include <zmq.hpp>

#include "sadr/wire/rpc.hpp"

namespace sadr::wire::detail {

/// Sets up PLAIN or CURVE on a server socket before bind; returns the ZAP
/// domain registered for it ("" when the socket accepts everyone).
std::string secure_server(zmq::socket_t& socket, const ServerOptions& options);
/// Forgets a domain returned by secure_server (the socket is gone).
void release_domain(const std::string& domain);
/// Applies the credentials registered for `endpoint`, if any, before connect.
/// Returns "PLAIN", "CURVE" or "NULL" (for messages).
std::string secure_client(zmq::socket_t& socket, const std::string& endpoint);

}  // namespace sadr::wire::detail
