// SPDX-License-Identifier: MIT
// Shared by the ssa_service layer tests: the handler called in-process, and a 1D box.
#pragma once

#include "sadr/ssa/ssa_service.hpp"
#include "sadr/wire/convert.hpp"

namespace sadr::ssa::testing {

/// The service's request handler, called without a socket.
class Probe : public SsaServiceHandler {
 public:
  void call(const v1::SsaRequest& request, v1::SsaReply& reply) {
    bool shutdown = false;
    handle_typed(request, reply, shutdown);
  }
};

/// The model's box: the line [0, length] (y, z of unit extent), periodic or walled.
inline void set_line_box(v1::SsaModel& m, double length, bool periodic) {
  Box box;
  box.dimension = 1;
  box.lo = {0, 0, 0};
  box.hi = {length, 1, 1};
  box.periodic = {periodic, false, false};
  wire::to_proto(box, *m.mutable_box());
}

}  // namespace sadr::ssa::testing
