// SPDX-License-Identifier: MIT
/// \file peer_table.hpp
/// Private to sadr::wire: what a server knows about its peers, kept from its
/// socket's monitor events (ZMQ_ROUTER_NOTIFY is a draft API in libzmq 4.3).
///
/// * Handshaken peers are keyed by (routing id, connection fd); an entry is
///   dropped when its connection closes or a new connection gets its fd, so a
///   new peer reusing a routing id must redo the handshake. The table is also
///   bounded (least recently used entries go first) for transports without
///   connection events (inproc).
/// * Connections accepted but not yet past the ZeroMQ security handshake
///   ("pending") are bounded in number: above the limit, the oldest is shut
///   down. With the per-frame limit (kMaxFrameBytes) this bounds what peers
///   without credentials can make the server hold.
#pragma once

#include <cstddef>
#include <cstdint>
#include <list>
#include <map>
#include <string>
#include <utility>

#include "zmq_support.hpp"

namespace sadr::wire::detail {

class PeerTable {
 public:
  PeerTable(std::size_t max_peers, std::size_t max_pending)
      : max_peers_(max_peers), max_pending_(max_pending) {}

  /// ACCEPTED / DISCONNECTED / CLOSED events of the server socket.
  void on_event(const MonitorEvent& e);
  /// A message arrived from connection `fd`: it passed the security handshake.
  void saw_message(int fd) { pending_.erase(fd); }
  [[nodiscard]] bool handshaken(const std::string& id, int fd);
  void mark_handshaken(const std::string& id, int fd);
  /// Shuts down the oldest pending connections above the limit; returns how many.
  std::size_t enforce_pending_limit();

  [[nodiscard]] std::size_t peers() const { return peers_.size(); }
  [[nodiscard]] std::size_t pending() const { return pending_.size(); }

 private:
  void drop_fd(int fd);

  std::size_t max_peers_, max_pending_;
  using Key = std::pair<std::string, int>;  // (routing id, fd; -1 without one)
  std::list<Key> lru_;                      // most recently used first
  std::map<Key, std::list<Key>::iterator> peers_;
  std::map<int, std::uint64_t> pending_;  // fd -> accept order
  std::uint64_t accepted_ = 0;
};

}  // namespace sadr::wire::detail
