// SPDX-License-Identifier: MIT
#include "peer_table.hpp"

#include <sys/socket.h>

#include <algorithm>

namespace sadr::wire::detail {

void PeerTable::drop_fd(int fd) {
  for (auto it = peers_.begin(); it != peers_.end();) {
    if (it->first.second == fd) {
      lru_.erase(it->second);
      it = peers_.erase(it);
    } else {
      ++it;
    }
  }
  pending_.erase(fd);
}

void PeerTable::on_event(const MonitorEvent& e) {
  if (e.value < 0) return;
  switch (e.event) {
    case ZMQ_EVENT_ACCEPTED:
      drop_fd(e.value);  // a new connection on a reused fd number
      pending_[e.value] = accepted_++;
      break;
    case ZMQ_EVENT_DISCONNECTED:
    case ZMQ_EVENT_CLOSED:
      drop_fd(e.value);
      break;
    default:
      break;
  }
}

bool PeerTable::handshaken(const std::string& id, int fd) {
  const auto it = peers_.find({id, fd});
  if (it == peers_.end()) return false;
  lru_.splice(lru_.begin(), lru_, it->second);
  return true;
}

void PeerTable::mark_handshaken(const std::string& id, int fd) {
  if (handshaken(id, fd)) return;
  lru_.push_front({id, fd});
  peers_[{id, fd}] = lru_.begin();
  while (peers_.size() > max_peers_) {
    peers_.erase(lru_.back());
    lru_.pop_back();
  }
}

std::size_t PeerTable::enforce_pending_limit() {
  std::size_t cut = 0;
  while (pending_.size() > max_pending_) {
    const auto oldest = std::min_element(pending_.begin(), pending_.end(),
                                         [](auto& a, auto& b) { return a.second < b.second; });
    // The fd stays libzmq's: shutdown() only makes its next read end, and
    // libzmq then closes the connection itself (a DISCONNECTED event follows).
    ::shutdown(oldest->first, SHUT_RDWR);
    pending_.erase(oldest);
    ++cut;
  }
  return cut;
}

}  // namespace sadr::wire::detail
