// SPDX-License-Identifier: MIT
#include "auth.hpp"

#include <unistd.h>
#include <zmq_addon.hpp>

#include <atomic>
#include <future>
#include <map>
#include <mutex>
#include <set>
#include <thread>
#include <vector>

#include "sadr/common/log.hpp"
#include "zmq_support.hpp"

namespace sadr::wire {
namespace detail {
namespace {

/// What one server socket (ZAP domain) accepts.
struct Policy {
  std::string secret;                ///< PLAIN password; empty with CURVE
  std::set<std::string> curve_keys;  ///< authorized client public keys (32 raw bytes)
};

std::mutex g_mutex;
std::map<std::string, Policy> g_domains;                  // ZAP domain -> policy
std::map<std::string, ClientCredentials> g_client_creds;  // endpoint -> credentials
std::atomic<unsigned long> g_refused{0};

bool same_secret(std::string_view a, std::string_view b) {
  unsigned diff = a.size() == b.size() ? 0u : 1u;  // constant time in the content
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) {
    diff |= static_cast<unsigned char>(a[i]) ^ static_cast<unsigned char>(b[i]);
  }
  return diff == 0;
}

std::string raw_key(const std::string& z85) {
  std::string out(32, '\0');
  zmq_z85_decode(reinterpret_cast<std::uint8_t*>(out.data()), z85.c_str());
  return out;
}

/// ZAP request [version, id, domain, address, identity, mechanism, credentials...].
bool accepted(const std::vector<zmq::message_t>& req) {
  if (req.size() < 6) return false;
  std::lock_guard lock(g_mutex);
  const auto it = g_domains.find(req[2].to_string());
  if (it == g_domains.end()) return true;  // a socket that did not ask for checks
  const Policy& p = it->second;
  const std::string mechanism = req[5].to_string();
  if (!p.secret.empty()) {
    return mechanism == "PLAIN" && req.size() >= 8 && same_secret(view(req[7]), p.secret);
  }
  return mechanism == "CURVE" && req.size() >= 7 && p.curve_keys.count(req[6].to_string()) > 0;
}

void zap_loop(std::promise<void>* bound) {
  zmq::socket_t zap(shared_context(), zmq::socket_type::rep);
  zap.bind("inproc://zeromq.zap.01");
  bound->set_value();
  for (;;) {
    std::vector<zmq::message_t> req;
    try {
      if (!zmq::recv_multipart(zap, std::back_inserter(req))) continue;
    } catch (const zmq::error_t&) {
      continue;
    }
    const bool ok = accepted(req);
    if (!ok) {
      // Logged for the first few and then at powers of two: a flood of
      // refused connections must not become a flood of log lines.
      const unsigned long n = ++g_refused;
      if (n <= 3 || (n & (n - 1)) == 0) {
        log::warn("refused a connection without the run's secret or an authorized key (from ",
                  shorten(req.size() > 3 ? req[3].to_string() : std::string("?")), ", ",
                  shorten(req.size() > 5 ? req[5].to_string() : std::string("?"), 8),
                  "; refused so far: ", n, ")");
      }
    }
    std::vector<zmq::message_t> out;
    out.emplace_back(std::string_view("1.0"));
    if (req.size() > 1) {
      out.emplace_back(req[1].data(), req[1].size());
    } else {
      out.emplace_back();
    }
    out.emplace_back(std::string_view(ok ? "200" : "400"));
    out.emplace_back(std::string_view(ok ? "OK" : "no run secret or authorized key"));
    out.emplace_back(std::string_view("sadr"));
    out.emplace_back();
    zmq::send_multipart(zap, out);
  }
}

void ensure_zap_handler() {
  static std::once_flag once;
  std::call_once(once, [] {
    std::promise<void> bound;
    std::thread(zap_loop, &bound).detach();
    bound.get_future().wait();
  });
}

}  // namespace

std::string secure_server(zmq::socket_t& s, const ServerOptions& options) {
  if (options.secret.empty() && !options.curve) return {};
  if (!options.secret.empty() && options.curve) {
    throw Error(StatusCode::kInvalidArgument,
                "a service takes either the run's secret (PLAIN) or CURVE keys, not both");
  }
  ensure_zap_handler();
  static std::atomic<unsigned> counter{0};
  std::string domain = "sadr-" + std::to_string(getpid()) + "-" + std::to_string(counter++);
  Policy policy;
  policy.secret = options.secret;
  if (options.curve) {
    for (const auto& k : options.curve->authorized_clients) policy.curve_keys.insert(raw_key(k));
  }
  {
    std::lock_guard lock(g_mutex);
    g_domains[domain] = std::move(policy);
  }
  s.set(zmq::sockopt::zap_domain, domain);
  if (options.curve) {
    s.set(zmq::sockopt::curve_server, 1);
    s.set(zmq::sockopt::curve_secretkey, options.curve->keys.secret_key);
  } else {
    s.set(zmq::sockopt::plain_server, 1);
  }
  return domain;
}

void release_domain(const std::string& domain) {
  if (domain.empty()) return;
  std::lock_guard lock(g_mutex);
  g_domains.erase(domain);
}

std::string secure_client(zmq::socket_t& s, const std::string& endpoint) {
  std::lock_guard lock(g_mutex);
  const auto it = g_client_creds.find(endpoint);
  if (it == g_client_creds.end()) return "NULL";
  const ClientCredentials& c = it->second;
  if (!c.server_public_key.empty()) {
    s.set(zmq::sockopt::curve_serverkey, c.server_public_key);
    s.set(zmq::sockopt::curve_publickey, c.keys.public_key);
    s.set(zmq::sockopt::curve_secretkey, c.keys.secret_key);
    return "CURVE";
  }
  s.set(zmq::sockopt::plain_username, "sadr");
  s.set(zmq::sockopt::plain_password, c.secret);
  return "PLAIN";
}

}  // namespace detail

void set_client_credentials(const std::string& endpoint, const ClientCredentials& credentials) {
  std::lock_guard lock(detail::g_mutex);
  if (credentials.secret.empty() && credentials.server_public_key.empty()) {
    detail::g_client_creds.erase(endpoint);
  } else {
    detail::g_client_creds[endpoint] = credentials;
  }
}

void set_client_secret(const std::string& endpoint, const std::string& secret) {
  ClientCredentials c;
  c.secret = secret;
  set_client_credentials(endpoint, c);
}

}  // namespace sadr::wire
