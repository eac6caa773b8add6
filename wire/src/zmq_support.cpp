// SPDX-License-Identifier: MIT
#include "zmq_support.hpp"

#include <atomic>
#include <cstring>

#include "sadr/common/status.hpp"

namespace sadr::wire::detail {

zmq::socket_t monitor_socket(zmq::socket_t& socket, int events, bool unbounded) {
  static std::atomic<unsigned long> counter{0};
  const std::string address = "inproc://sadr-monitor-" + std::to_string(counter++);
  if (zmq_socket_monitor(socket.handle(), address.c_str(), events) != 0) {
    throw Error(StatusCode::kInternal,
                "zmq_socket_monitor failed: " + std::string(zmq_strerror(zmq_errno())));
  }
  zmq::socket_t pair(shared_context(), zmq::socket_type::pair);
  pair.set(zmq::sockopt::linger, 0);
  if (unbounded) pair.set(zmq::sockopt::rcvhwm, 0);  // inproc: 0 on either side = no limit
  pair.connect(address);
  return pair;
}

bool next_event(zmq::socket_t& monitor, MonitorEvent& out) {
  zmq::message_t head, address;
  if (!monitor.recv(head, zmq::recv_flags::dontwait)) return false;
  if (head.more()) (void)monitor.recv(address, zmq::recv_flags::none);
  if (head.size() < 6) return false;
  std::uint16_t ev = 0;
  std::uint32_t value = 0;
  std::memcpy(&ev, head.data(), 2);
  std::memcpy(&value, static_cast<const char*>(head.data()) + 2, 4);
  out.event = ev;
  out.value = static_cast<int>(value);
  return true;
}

}  // namespace sadr::wire::detail
