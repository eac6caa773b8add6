// SPDX-License-Identifier: MIT
/// \file fuzz_restore.hpp
/// The body of the snapshot-restore targets: a handler initialised with
/// kSmallScene restores a snapshot whose blob is the input (after one byte
/// that picks the fluid backend), then advances once and snapshots again, so
/// a blob that restores into an inconsistent state is caught when it is used.
#pragma once

#include "fuzz_messages.hpp"

namespace sadr::fuzz {

/// `Handler` is FluidServiceHandler or SsaServiceHandler; `Request`/`Reply`
/// its message pair; `init` the Init request; `format` the snapshot's
/// format and version (as the service writes them).
template <class Handler, class Request, class Reply, class Init>
void restore_and_step(const Init& init, const common::v1::Snapshot& format, std::string_view blob,
                      std::string_view what) {
  Handler handler;
  bool shutdown = false;
  auto call = [&](const Request& req) {
    const std::string out = handler.handle(req.SerializeAsString(), shutdown);
    Reply rep;
    if (!rep.ParseFromString(out)) std::abort();
    require_diagnosed(rep.status(), what);
    return rep.status().code() == 0;
  };
  Request req;
  *req.mutable_init() = init;
  if (!call(req)) std::abort();  // the built-in Init must work
  req.Clear();
  auto* snap = req.mutable_restore()->mutable_snapshot();
  *snap = format;
  snap->set_blob(std::string(blob));
  if (!call(req)) return;  // refused: fine, as long as it is diagnosed
  req.Clear();
  auto* adv = req.mutable_advance();
  adv->set_run_id("fuzz");
  adv->set_step_index(format.step_index() + 1);
  if constexpr (requires { adv->set_time_step(0.05); }) {
    adv->set_time_step(0.05);
  } else {
    adv->set_t_end(format.time() + 0.05);
  }
  call(req);
  req.Clear();
  req.mutable_snapshot()->set_step_index(1);
  call(req);
}

/// The snapshot a freshly initialised handler takes (format, version, time;
/// blob cleared): the envelope the fuzzed blobs travel in.
template <class Handler, class Request, class Reply, class Init>
common::v1::Snapshot snapshot_envelope(const Init& init) {
  Handler handler;
  bool shutdown = false;
  Request req;
  *req.mutable_init() = init;
  handler.handle(req.SerializeAsString(), shutdown);
  req.Clear();
  req.mutable_snapshot()->set_step_index(0);
  Reply rep;
  if (!rep.ParseFromString(handler.handle(req.SerializeAsString(), shutdown)) ||
      rep.status().code() != 0) {
    std::fprintf(stderr, "fuzz: the built-in scene does not snapshot: %s\n",
                 rep.status().message().c_str());
    std::abort();
  }
  common::v1::Snapshot s = rep.snapshot().snapshot();
  s.clear_blob();
  return s;
}

}  // namespace sadr::fuzz
