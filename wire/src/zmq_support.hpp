// SPDX-License-Identifier: MIT
/// \file zmq_support.hpp
/// Private to sadr::wire: the process's ZeroMQ context and message helpers.
#pragma once

#include <string>
#include <string_view>
#include <zmq.hpp>

namespace sadr::wire::detail {

/// One context per process, never destroyed: inproc endpoints need a shared
/// context, and a context torn down at exit would block on sockets that
/// detached threads still hold.
inline zmq::context_t& shared_context() {
  static auto* ctx = new zmq::context_t(1);
  return *ctx;
}

inline std::string_view view(const zmq::message_t& m) {
  return {static_cast<const char*>(m.data()), m.size()};
}

/// A monitor event: [u16 event][u32 value] then the endpoint frame.
struct MonitorEvent {
  unsigned event = 0;
  int value = 0;
};

/// Starts monitoring `socket` for `events` and returns the connected PAIR
/// socket that receives them. libzmq's I/O thread blocks when 1000 events
/// wait unread: a server accepts that (it stops accepting connections until
/// its loop reads them); a client, which reads them only during calls, asks
/// for `unbounded` so that an idle client never stalls the I/O thread that
/// its process's other sockets share.
zmq::socket_t monitor_socket(zmq::socket_t& socket, int events, bool unbounded = false);
/// Stops monitoring `socket`. Must come before the monitor socket closes:
/// libzmq's I/O thread blocks on events that nobody can receive any more.
inline void stop_monitor(zmq::socket_t& socket) {
  zmq_socket_monitor(socket.handle(), nullptr, 0);
}
/// Reads one pending event (non-blocking); false when none is pending.
bool next_event(zmq::socket_t& monitor, MonitorEvent& out);

}  // namespace sadr::wire::detail
