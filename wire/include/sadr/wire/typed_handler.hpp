// SPDX-License-Identifier: MIT
/// \file typed_handler.hpp
/// RequestHandler for one (Request, Reply) protobuf pair: parses the body,
/// calls the service's typed handler, and turns every exception into the
/// reply's Status. `Reply` must have a `status` field (sadr.common.v1.Status).
#pragma once

#include <exception>
#include <string>

#include "sadr/common/log.hpp"
#include "sadr/wire/convert.hpp"
#include "sadr/wire/rpc.hpp"

namespace sadr::wire {

template <class Request, class Reply>
class TypedHandler : public RequestHandler {
 public:
  std::string_view request_type() const final { return Request::descriptor()->full_name(); }
  std::string_view reply_type() const final { return Reply::descriptor()->full_name(); }

  std::string handle(std::string_view body, bool& shutdown) final {
    Request request;
    Reply reply;
    if (!request.ParseFromArray(body.data(), static_cast<int>(body.size()))) {
      to_proto(Status{StatusCode::kInvalidArgument,
                      "malformed request: " + std::to_string(body.size()) +
                          " bytes that do not parse as " + std::string(request_type()),
                      {}},
               *reply.mutable_status());
    } else {
      try {
        handle_typed(request, reply, shutdown);
      } catch (const std::exception& e) {
        const Status st = status_from_exception(e);
        log::warn("request failed: ", st.to_string());
        reply.Clear();
        to_proto(st, *reply.mutable_status());
      }
    }
    std::string out;
    reply.SerializeToString(&out);
    return out;
  }

 protected:
  /// Fills `reply` (status OK is the default) or throws sadr::Error.
  virtual void handle_typed(const Request& request, Reply& reply, bool& shutdown) = 0;
};

}  // namespace sadr::wire
